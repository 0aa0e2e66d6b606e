// intersection program `pulsing_sphere`
fn rt_report_intersection_Normals(material: u32, attr: ptr<function, Normals>) -> bool { return false; }

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

fn rtp_pulsing_sphere(attr: ptr<function, Normals>, prim: u32) {
    _ = prim;
    let ray: RtRay = rt_current_ray();
    let r: f32 = (0.5f + (0.25f * clamp(rt_current_time(), 0.0f, 1.0f)));
    let b: f32 = dot(ray.origin, ray.direction);
    let c: f32 = (dot(ray.origin, ray.origin) - (r * r));
    let a: f32 = dot(ray.direction, ray.direction);
    let disc: f32 = ((b * b) - (a * c));
    if (disc > 0.0f) {
        let t: f32 = ((-b - sqrt(disc)) / a);
        if rt_potential_intersection(t) {
            let n: vec3<f32> = ((ray.origin + (t * ray.direction)) / r);
            (*attr).geometric_normal = n;
            (*attr).shading_normal = n;
            _ = rt_report_intersection_Normals(0u, attr);
        }
    }
}
