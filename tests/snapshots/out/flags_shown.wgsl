// miss program `flags_shown`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_flags_shown(prd: ptr<function, Radiance>) {
    (*prd).result = (vec3<f32>(f32(rt_ray_flags()), f32(rt_ray_mask()), 0.0f) / 255.0f);
}
