// ray_generation program `march_volume`

fn rt_bufload2_f32(b: RtBuffer, i: vec2<u32>) -> f32 {
    if rt_buf_check2(b, i) {
        return rt_load_f32(b.offset + (i.y * b.width + i.x) * 1u);
    }
    return f32();
}

fn rt_bufload3_f32(b: RtBuffer, i: vec3<u32>) -> f32 {
    if rt_buf_check3(b, i) {
        return rt_load_f32(b.offset + ((i.z * b.height + i.y) * b.width + i.x) * 1u);
    }
    return f32();
}

fn rt_bufload3_u32(b: RtBuffer, i: vec3<u32>) -> u32 {
    if rt_buf_check3(b, i) {
        return rt_load_u32(b.offset + ((i.z * b.height + i.y) * b.width + i.x) * 1u);
    }
    return u32();
}

fn rt_bufstore2_f32(b: RtBuffer, i: vec2<u32>, v: f32) {
    if rt_buf_check2(b, i) {
        rt_store_f32(b.offset + (i.y * b.width + i.x) * 1u, v);
    }
}

fn rt_bufstore3_u32(b: RtBuffer, i: vec3<u32>, v: u32) {
    if rt_buf_check3(b, i) {
        rt_store_u32(b.offset + ((i.z * b.height + i.y) * b.width + i.x) * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtp_march_volume(density: RtBuffer, out: RtBuffer, seen: RtBuffer) {
    var out_1 = out;
    var seen_1 = seen;
    let l: vec2<u32> = rt_launch_index();
    let size: vec3<u32> = rt_buf_size3(density);
    var sum: f32 = 0.0f;
    var z: u32 = 0u;
    while (z < size.z) {
        let cell: vec3<u32> = vec3<u32>(l.x, l.y, z);
        sum += rt_bufload3_f32(density, cell);
        let tmp = cell;
        rt_bufstore3_u32(seen_1, tmp, (rt_bufload3_u32(seen_1, cell) + 1u));
        z += 1u;
    }
    let tmp_1 = l;
    rt_bufstore2_f32(out_1, tmp_1, (sum / f32(size.z)));
}
