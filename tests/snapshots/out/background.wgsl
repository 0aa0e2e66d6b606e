// miss program `background`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_background(prd: ptr<function, Radiance>, bg_color: vec3<f32>) {
    (*prd).result = bg_color;
}
