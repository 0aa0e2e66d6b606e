// intersection program `sphere_intersect`
fn rt_report_intersection_Normals(material: u32, attr: ptr<function, Normals>) -> bool { return false; }

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rtp_sphere_intersect(attr: ptr<function, Normals>, prim: u32, spheres: RtBuffer) {
    let s: vec4<f32> = rt_bufload_vec4f(spheres, prim);
    let center: vec3<f32> = s.xyz;
    let radius: f32 = s.w;
    let ray: RtRay = rt_current_ray();
    let o: vec3<f32> = (ray.origin - center);
    let b: f32 = dot(o, ray.direction);
    let c: f32 = (dot(o, o) - (radius * radius));
    let disc: f32 = ((b * b) - c);
    if (disc < 0.0f) {
        return;
    }
    let sdisc: f32 = sqrt(disc);
    var roots: array<f32, 2> = array<f32, 2>((-b - sdisc), (-b + sdisc));
    var i: u32 = 0u;
    while (i < 2u) {
        let t: f32 = roots[i];
        if rt_potential_intersection(t) {
            let n: vec3<f32> = ((o + (t * ray.direction)) / radius);
            (*attr).geometric_normal = n;
            (*attr).shading_normal = n;
            if rt_report_intersection_Normals(0u, attr) {
                break;
            }
        }
        i += 1u;
    }
}
