// ray_generation program `compare_logic`

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

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtf_counted_above(calls: ptr<function, u32>, v: f32, limit: f32) -> bool {
    (*calls) += 1u;
    return (v > limit);
}

fn rtp_compare_logic(x: f32, y: f32, n: i32, m: u32, a: vec3<f32>, b: vec3<f32>, out: RtBuffer) {
    let lt: bool = (x < y);
    let le: bool = (x <= y);
    let gt: bool = (n > -3i);
    let ge: bool = (m >= 10u);
    let eq: bool = ((n == 4i) || (m != 2u));
    let same: bool = all(a == b);
    let differ: bool = !all(a.xy == b.xy);
    var calls: u32 = 0u;
    let both: bool = (lt && rtf_counted_above(&calls, y, 0.5f));
    let either: bool = (ge || rtf_counted_above(&calls, x, -0.5f));
    let chained: bool = (!(le && gt) || ((x > 0.0f) && rtf_counted_above(&calls, (x + y), 1.0f)));
    let all_: bool = ((le & gt) & !eq);
    let any_: bool = (same | differ);
    let one: bool = (both != either);
    var flags: u32 = 0u;
    if all_ {
        flags |= 1u;
    }
    if any_ {
        flags |= 2u;
    }
    flags |= (u32(one) << 2u);
    flags |= (u32(chained) << 3u);
    flags |= (u32((same != differ)) << 4u);
    rt_bufstore_u32(out, rt_launch_index().x, (flags + (calls * 256u)));
}
