// ray_generation program `fuzz_bitwise_compound`

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

fn rtp_fuzz_bitwise_compound(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    var v: array<vec2<u32>, 2> = array<vec2<u32>, 2>(vec2<u32>(a, 7u), vec2<u32>(3u, (a ^ 5u)));
    v[0u] &= (v[1u] | vec2<u32>(u32(b)));
    v[1u] ^= v[0u];
    var m: array<u32, 2> = array<u32, 2>(a, (a + 1u));
    m[1u] |= (m[0u] << 2u);
    rt_bufstore_u32(out_u, slot, (v[0u].x + v[0u].y));
    rt_bufstore_u32(out_u, (slot + 1u), (v[1u].x ^ v[1u].y));
    rt_bufstore_u32(out_u, (slot + 2u), m[1u]);
    rt_bufstore_f32(out_f, slot, x);
}
