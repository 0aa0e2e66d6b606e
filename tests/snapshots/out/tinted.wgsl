// callable program `tinted`

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rtp_tinted(strength: f32, ramp: RtBuffer, c: vec3<f32>) -> vec3<f32> {
    return ((c * strength) * rt_bufload_f32(ramp, 0u));
}
