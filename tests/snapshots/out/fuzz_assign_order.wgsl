// ray_generation program `fuzz_assign_order`

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

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
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

const SLOTS: u32 = 8u;

fn rtp_fuzz_assign_order(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    var source: array<u32, 3> = array<u32, 3>(a, (a + 1u), (a + 2u));
    var dest: array<u32, 3> = array<u32, 3>(0u, 0u, 0u);
    let tmp_1 = source[0u];
    var tmp: i32;
    if (b > 0i) {
        source[0u] = 7u;
        tmp = 1i;
    } else {
        tmp = 2i;
    }
    dest[u32(tmp)] = tmp_1;
    rt_bufstore_u32(out_u, slot, dest[0u]);
    rt_bufstore_u32(out_u, (slot + 1u), dest[1u]);
    rt_bufstore_u32(out_u, (slot + 2u), dest[2u]);
    rt_bufstore_u32(out_u, (slot + 3u), source[0u]);
    rt_bufstore_f32(out_f, slot, x);
}
