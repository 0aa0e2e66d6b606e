// ray_generation program `checked_fill`

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

const ERR_BAD_SCALE: u32 = (1024u + 1u);

fn rtp_checked_fill(scale: f32, values: RtBuffer, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = (rt_launch_index().x + (rt_launch_index().y * rt_launch_dim().x));
    if (!(abs(scale) <= 0x1.fffffep+127f) || (scale <= 0.0f)) {
        rt_throw(ERR_BAD_SCALE);
        return;
    }
    if (i >= values.len) {
        rt_throw(1024u);
        return;
    }
    let tmp = i;
    rt_bufstore_f32(out_1, tmp, (rt_bufload_f32(values, i) * scale));
}
