// ray_generation program `tuples_inferred`

struct rt_tuple_i32_u32_ {
    f0: i32,
    f1: u32,
}

struct rt_tuple_rt_tuple_i32_u32__i32_ {
    f0: rt_tuple_i32_u32_,
    f1: i32,
}

struct rt_tuple_u32_f32_ {
    f0: u32,
    f1: f32,
}

struct rt_tuple_u32_i32_ {
    f0: u32,
    f1: i32,
}

fn rt_bufload_u32(b: RtBuffer, i: u32) -> u32 {
    if rt_buf_check(b, i) {
        return rt_load_u32(b.offset + i * 1u);
    }
    return u32();
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtp_tuples_inferred(out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let t: rt_tuple_u32_f32_ = rt_tuple_u32_f32_(5u, 2.0f);
    let x: u32 = (t.f0 + i);
    let tuple: rt_tuple_u32_i32_ = rt_tuple_u32_i32_(7u, 1i);
    let a: u32 = tuple.f0;
    let b: i32 = tuple.f1;
    let y: u32 = (a + i);
    let n: rt_tuple_rt_tuple_i32_u32__i32_ = rt_tuple_rt_tuple_i32_u32__i32_(rt_tuple_i32_u32_(1i, 4294967295u), 3i);
    let z: u32 = n.f0.f1;
    var m: rt_tuple_u32_f32_ = rt_tuple_u32_f32_(3u, 0.5f);
    m.f0 += i;
    let tmp = i;
    rt_bufstore_u32(out_1, tmp, (((((x + y) + z) + m.f0) + u32(((b + n.f1) + n.f0.f0))) + rt_f2u(t.f1)));
}
