// miss program `shadow_miss`

struct Shadow {
    attenuation: vec3<f32>,
}

fn rtp_shadow_miss(prd: ptr<function, Shadow>) {
    (*prd).attenuation = max((*prd).attenuation, vec3<f32>(0.0));
}
