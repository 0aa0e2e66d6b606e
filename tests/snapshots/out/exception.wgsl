// exception program `exception`

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

fn rtp_exception(bad_color: vec3<f32>, output_buffer: RtBuffer) {
    var output_buffer_1 = output_buffer;
    let tmp = rt_launch_index();
    rt_bufstore2_vec4f(output_buffer_1, tmp, vec4<f32>(bad_color, 1.0f));
}
