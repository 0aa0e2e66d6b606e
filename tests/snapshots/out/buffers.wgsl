// ray_generation program `buffers`

struct Bin {
    sum: vec3<f32>,
    count: u32,
    max_value: f32,
}

fn rt_bufload_Bin(b: RtBuffer, i: u32) -> Bin {
    if rt_buf_check(b, i) {
        return rt_load_Bin(b.offset + i * 5u);
    }
    return Bin();
}

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_bufload_u32(b: RtBuffer, i: u32) -> u32 {
    if rt_buf_check(b, i) {
        return rt_load_u32(b.offset + i * 1u);
    }
    return u32();
}

fn rt_bufload_vec3f(b: RtBuffer, i: u32) -> vec3<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec3f(b.offset + i * 3u);
    }
    return vec3<f32>();
}

fn rt_bufstore_Bin(b: RtBuffer, i: u32, v: Bin) {
    if rt_buf_check(b, i) {
        rt_store_Bin(b.offset + i * 5u, v);
    }
}

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_load_Bin(w: u32) -> Bin {
    return Bin(rt_load_vec3f(w + 0u), rt_load_u32(w + 3u), rt_load_f32(w + 4u));
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

fn rt_store_Bin(w: u32, v: Bin) {
    rt_store_vec3f(w + 0u, v.sum);
    rt_store_u32(w + 3u, v.count);
    rt_store_f32(w + 4u, v.max_value);
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rt_store_vec3f(w: u32, v: vec3<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
}

fn rtp_buffers(samples: RtBuffer, bin_of: RtBuffer, bins: RtBuffer, totals: RtBuffer, order: RtBuffer) {
    var bins_1 = bins;
    var totals_1 = totals;
    var order_1 = order;
    let i: u32 = rt_launch_index().x;
    if ((samples.len == 0u) || (i >= samples.len)) {
        return;
    }
    let s: vec3<f32> = rt_bufload_vec3f(samples, i);
    let b: u32 = (rt_bufload_u32(bin_of, i) % bins_1.len);
    let tmp = b;
    var tmp_1 = rt_bufload_Bin(bins_1, tmp);
    tmp_1.sum += s;
    rt_bufstore_Bin(bins_1, tmp, tmp_1);
    let tmp_2 = b;
    var tmp_3 = rt_bufload_Bin(bins_1, tmp_2);
    tmp_3.count += 1u;
    rt_bufstore_Bin(bins_1, tmp_2, tmp_3);
    if (max(max(s.x, s.y), s.z) > rt_bufload_Bin(bins_1, b).max_value) {
        let tmp_4 = b;
        var tmp_5 = rt_bufload_Bin(bins_1, tmp_4);
        tmp_5.max_value = max(max(s.x, s.y), s.z);
        rt_bufstore_Bin(bins_1, tmp_4, tmp_5);
    }
    var bin: Bin = rt_bufload_Bin(bins_1, b);
    bin.sum *= 0.5f;
    rt_bufstore_Bin(bins_1, ((b + 1u) % bins_1.len), bin);
    let tmp_6 = i;
    rt_bufstore_f32(totals_1, tmp_6, (s.x + s.y + s.z));
    let tmp_7 = i;
    var tmp_8 = rt_bufload_f32(totals_1, tmp_7);
    tmp_8 += (rt_bufload_f32(totals_1, i) * 0.5f);
    rt_bufstore_f32(totals_1, tmp_7, tmp_8);
    rt_bufstore_u32(order_1, i, (rt_bufload_u32(order_1, i) + samples.len));
    let tmp_9 = i;
    var tmp_10 = rt_bufload_u32(order_1, tmp_9);
    tmp_10 |= 1u;
    rt_bufstore_u32(order_1, tmp_9, tmp_10);
}
