// miss program `fog_footprint`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_fog_footprint(prd: ptr<function, Radiance>, fog: RtSampler3d, fog_id: u32, bounds: vec3<f32>) {
    let ray: RtRay = rt_current_ray();
    let uvw: vec3<f32> = ((ray.origin + ray.direction) / bounds);
    let step_: f32 = (1.0f / f32(rt_launch_dim().x));
    let dx: vec3<f32> = (vec3<f32>(step_, 0.0f, 0.0f) / bounds);
    let dy: vec3<f32> = (vec3<f32>(0.0f, step_, 0.0f) / bounds);
    let tmp = rt_texid3(fog_id);
    (*prd).result = (rt_tex3_sample_grad(fog, uvw, dx, dy).xyz + rt_tex3_sample_grad(tmp, uvw, dx, dy).xyz);
}
