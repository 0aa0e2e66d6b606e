// miss program `path_sky`

struct PathState {
    radiance: vec3<f32>,
    throughput: vec3<f32>,
    origin: vec3<f32>,
    direction: vec3<f32>,
    seed: u32,
    done: bool,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_path_sky(prd: ptr<function, PathState>, sky: vec3<f32>) {
    (*prd).radiance += (((*prd).throughput * sky) * (0.5f + (0.5f * rt_current_ray().direction.y)));
    (*prd).done = true;
}
