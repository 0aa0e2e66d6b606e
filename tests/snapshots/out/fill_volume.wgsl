// ray_generation program `fill_volume`

fn rt_bufload3_vec4f(b: RtBuffer, i: vec3<u32>) -> vec4<f32> {
    if rt_buf_check3(b, i) {
        return rt_load_vec4f(b.offset + ((i.z * b.height + i.y) * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore3_vec4f(b: RtBuffer, i: vec3<u32>, v: vec4<f32>) {
    if rt_buf_check3(b, i) {
        rt_store_vec4f(b.offset + ((i.z * b.height + i.y) * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
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

fn rtp_fill_volume(volume: RtBuffer) {
    var volume_1 = volume;
    let i: vec3<u32> = rt_launch_index_3d();
    let d: vec3<u32> = rt_launch_dim_3d();
    let tmp = i;
    rt_bufstore3_vec4f(volume_1, tmp, (vec4<f32>((vec3<f32>(i) + vec3<f32>(0.5f)), 1.0f) / vec4<f32>(vec3<f32>(d), 1.0f)));
}
