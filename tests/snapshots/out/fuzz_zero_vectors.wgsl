// ray_generation program `fuzz_zero_vectors`

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

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
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

fn rtp_fuzz_zero_vectors(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    let v: vec3<i32> = vec3<i32>(vec2<i32>(0i), b);
    rt_bufstore_u32(out_u, slot, u32(((v.x + v.y) + v.z)));
    let tmp = clamp(vec2<f32>(0.001f, 4.0f), vec2<f32>(-0.5f), vec2<f32>(0.0f));
    let n: vec2<f32> = select(vec2<f32>(), tmp * inverseSqrt(select(1.0, dot(tmp, tmp), dot(tmp, tmp) > 0.0)), dot(tmp, tmp) > 0.0);
    rt_bufstore_f32(out_f, slot, ((n.x + n.y) + x));
    rt_bufstore_u32(out_u, (slot + 1u), (rt_f2u(vec4<f32>(vec3<f32>(0.0), x).w) + a));
}
