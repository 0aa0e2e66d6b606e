// ray_generation program `buffers_2d`

fn rt_bufload2_u32(b: RtBuffer, i: vec2<u32>) -> u32 {
    if rt_buf_check2(b, i) {
        return rt_load_u32(b.offset + (i.y * b.width + i.x) * 1u);
    }
    return u32();
}

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore2_u32(b: RtBuffer, i: vec2<u32>, v: u32) {
    if rt_buf_check2(b, i) {
        rt_store_u32(b.offset + (i.y * b.width + i.x) * 1u, v);
    }
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

fn rtp_buffers_2d(input: RtBuffer, accum: RtBuffer, samples: RtBuffer, frame: u32) {
    var accum_1 = accum;
    var samples_1 = samples;
    let idx: vec2<u32> = rt_launch_index();
    let size: vec2<u32> = vec2<u32>(input.width, input.height);
    if ((idx.x >= size.x) || (idx.y >= size.y)) {
        return;
    }
    var sum: vec4<f32> = vec4<f32>(0.0);
    for (var dy: i32 = -1i; dy <= 1i; dy++) {
        for (var dx: i32 = -1i; dx <= 1i; dx++) {
            let p: vec2<i32> = clamp((vec2<i32>(idx) + vec2<i32>(dx, dy)), vec2<i32>(0i), (vec2<i32>(size) - 1i));
            sum += rt_bufload2_vec4f(input, vec2<u32>(p));
        }
    }
    let blurred: vec4<f32> = (sum / 9.0f);
    let prev: vec4<f32> = rt_bufload2_vec4f(accum_1, idx);
    let n: f32 = f32(rt_bufload2_u32(samples_1, idx));
    rt_bufstore2_vec4f(accum_1, idx, (((prev * n) + blurred) / (n + 1.0f)));
    let tmp = idx;
    var tmp_1 = rt_bufload2_u32(samples_1, tmp);
    tmp_1 += 1u;
    rt_bufstore2_u32(samples_1, tmp, tmp_1);
    if (frame == 0u) {
        let tmp_2 = idx;
        rt_bufstore2_vec4f(accum_1, tmp_2, blurred);
        let tmp_3 = vec2<u32>(idx.x, idx.y);
        rt_bufstore2_u32(samples_1, tmp_3, 1u);
    }
    let corner: vec2<u32> = (vec2<u32>(accum_1.width, accum_1.height) - vec2<u32>(1u));
    let tmp_4 = corner;
    rt_bufstore2_vec4f(accum_1, tmp_4, rt_bufload2_vec4f(input, vec2<u32>(0u)));
}
