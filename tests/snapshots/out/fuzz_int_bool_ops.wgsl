// ray_generation program `fuzz_int_bool_ops`

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

fn rtp_fuzz_int_bool_ops(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    var v: vec3<u32> = (vec3<u32>(a, (a + 1u), 3u) << vec3<u32>(u32((b & 7i))));
    v >>= vec3<u32>(u32((b & 3i)));
    rt_bufstore_u32(out_u, slot, ((v.x ^ v.y) ^ v.z));
    var flag: bool = (a > 3u);
    flag = (flag != (b < 0i));
    flag = (flag != true);
    rt_bufstore_u32(out_u, (slot + 1u), u32(flag));
    rt_bufstore_f32(out_f, slot, x);
}
