// callable program `blinn`
fn rt_call_f32__f32_(id: u32, a0: f32) -> f32 {
    var r: f32;
    return r;
}

fn rtf_half_vector(l: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    return normalize((l + v));
}

fn rtp_blinn(n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, exponent: u32) -> vec3<f32> {
    let tmp = rt_call_f32__f32_(exponent, dot(n, l));
    let e: f32 = tmp;
    return vec3<f32>(pow(max(dot(n, rtf_half_vector(l, v)), 0.0f), e));
}
