// ray_generation program `fuzz_shift_amounts`

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

fn rtp_fuzz_shift_amounts(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    rt_bufstore_u32(out_u, slot, (a >> (reverseBits(5u) & 31u)));
    let tmp = vec2<u32>(2278347882u);
    let v: vec2<i32> = (vec2<i32>(b) >> vec2<u32>(dot(tmp, vec2<u32>(8u))));
    rt_bufstore_u32(out_u, (slot + 1u), u32(v.x));
    let tmp_1 = vec3<u32>(4000000000u, 400000000u, 2u);
    rt_bufstore_u32(out_u, (slot + 2u), (tmp_1.x + tmp_1.y + tmp_1.z));
    rt_bufstore_f32(out_f, slot, x);
}
