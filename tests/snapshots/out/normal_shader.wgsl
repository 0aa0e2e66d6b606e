// closest_hit program `normal_shader`

struct Normals {
    geometric_normal: vec3<f32>,
    shading_normal: vec3<f32>,
}

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_normal_shader(prd: ptr<function, Radiance>, attr: Normals) {
    (*prd).result = ((normalize(rt_transform_normal(0u, attr.shading_normal)) * 0.5f) + 0.5f);
}
