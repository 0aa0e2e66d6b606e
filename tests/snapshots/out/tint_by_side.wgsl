// closest_hit program `tint_by_side`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_tint_by_side(prd: ptr<function, Radiance>, attr: Normals) {
    var c: vec3<f32> = ((attr.shading_normal * 0.5f) + vec3<f32>(0.5f));
    if rt_is_triangle_hit_front_face() {
        c = (c * 0.5f);
    }
    if (rt_ray_mask() != 255u) {
        c = (vec3<f32>(1.0) - c);
    }
    (*prd).result = c;
}
