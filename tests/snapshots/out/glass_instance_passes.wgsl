// any_hit program `glass_instance_passes`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtp_glass_instance_passes(prd: ptr<function, Shadow>, glass_id: u32) {
    if (rt_instance_id() == glass_id) {
        rt_ignore_intersection();
    }
    (*prd).attenuation = vec3<f32>(0.0);
}
