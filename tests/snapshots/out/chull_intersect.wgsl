// intersection program `chull_intersect`
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

fn rtp_chull_intersect(attr: ptr<function, Normals>, prim: u32, planes: RtBuffer) {
    _ = prim;
    let ray: RtRay = rt_current_ray();
    var t0: f32 = -0x1.fffffep+127f;
    var t1: f32 = 0x1.fffffep+127f;
    var t0_normal: vec3<f32> = vec3<f32>(0.0);
    var t1_normal: vec3<f32> = vec3<f32>(0.0);
    let n: u32 = planes.len;
    var i: u32 = 0u;
    while ((i < n) && (t0 < t1)) {
        let plane: vec4<f32> = rt_bufload_vec4f(planes, i);
        let normal: vec3<f32> = plane.xyz;
        let d: f32 = plane.w;
        let denom: f32 = dot(normal, ray.direction);
        let t: f32 = (-(d + dot(normal, ray.origin)) / denom);
        if (denom < 0.0f) {
            if (t > t0) {
                t0 = t;
                t0_normal = normal;
            }
        } else {
            if (t < t1) {
                t1 = t;
                t1_normal = normal;
            }
        }
        i += 1u;
    }
    if (t0 > t1) {
        return;
    }
    if rt_potential_intersection(t0) {
        (*attr).shading_normal = t0_normal;
        (*attr).geometric_normal = t0_normal;
        _ = rt_report_intersection_Normals(0u, attr);
    } else {
        if rt_potential_intersection(t1) {
            (*attr).shading_normal = t1_normal;
            (*attr).geometric_normal = t1_normal;
            _ = rt_report_intersection_Normals(0u, attr);
        }
    }
}
