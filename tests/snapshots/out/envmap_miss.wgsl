// miss program `envmap_miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtf_latlong_uv(d: vec3<f32>) -> vec2<f32> {
    let theta: f32 = atan2(d.x, d.z);
    let phi: f32 = (1.5707964f - acos(clamp(d.y, -1.0f, 1.0f)));
    return vec2<f32>(((theta + 3.1415927f) * (0.5f * 0.31830987f)), (0.5f * (1.0f + sin(phi))));
}

fn rtp_envmap_miss(prd: ptr<function, Radiance>, envmap: RtSampler) {
    (*prd).result = rt_tex_sample(envmap, rtf_latlong_uv(rt_current_ray().direction)).xyz;
}
