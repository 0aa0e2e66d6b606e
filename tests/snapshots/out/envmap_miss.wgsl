// miss program `envmap_miss`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rtp_envmap_miss(prd: ptr<function, Radiance>, envmap: RtSampler) {
    let d: vec3<f32> = rt_current_ray().direction;
    let theta: f32 = atan2(d.x, d.z);
    let phi: f32 = (1.5707964f - acos(d.y));
    let u: f32 = ((theta + 3.1415927f) * (0.5f * 0.31830987f));
    let v: f32 = (0.5f * (1.0f + sin(phi)));
    (*prd).result = rt_tex_sample(envmap, vec2<f32>(u, v)).xyz;
}
