// ray_generation program `fuzz_const_ints`

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

fn rtp_fuzz_const_ints(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    let tmp = 475240039u;
    rt_bufstore_u32(out_u, slot, ((tmp << 15u) ^ a));
    let tmp_1 = 2147483647i;
    rt_bufstore_u32(out_u, (slot + 1u), u32(((tmp_1 + 1i) ^ b)));
    let tmp_2 = vec2<i32>(2147483647i);
    let v: vec2<i32> = ((tmp_2 + vec2<i32>(1i)) * vec2<i32>(3i, b));
    rt_bufstore_u32(out_u, (slot + 2u), u32((v.x ^ v.y)));
    let tmp_3 = vec3<u32>(4000000000u, 1u, 2u);
    rt_bufstore_u32(out_u, (slot + 3u), ((tmp_3.x + tmp_3.y + tmp_3.z) ^ a));
    rt_bufstore_u32(out_u, (slot + 4u), (u32(select((a % select(0u, 1u, 0u == 0u)) == 0u, a == 0u, 0u == 0u)) + u32(select((7u % select(0u, 1u, 0u == 0u)) == 0u, 7u == 0u, 0u == 0u))));
    let tmp_4 = vec2<u32>(2147483649u);
    let w: vec2<u32> = (tmp_4 * vec2<u32>(3u));
    rt_bufstore_u32(out_u, (slot + 5u), (w.x ^ a));
    rt_bufstore_f32(out_f, slot, x);
}
