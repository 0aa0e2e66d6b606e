// any_hit program `glass_shadow`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_glass_shadow(prd: ptr<function, Shadow>, shadow_attenuation: vec3<f32>) {
    (*prd).attenuation *= shadow_attenuation;
    rt_ignore_intersection();
}
