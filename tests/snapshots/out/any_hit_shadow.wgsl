// any_hit program `any_hit_shadow`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rtp_any_hit_shadow(prd: ptr<function, Shadow>) {
    (*prd).attenuation = vec3<f32>(0.0);
    rt_terminate_ray();
}
