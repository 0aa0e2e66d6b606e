// closest_hit program `receiver_cell` (atomic heap)

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
}

fn rt_atomic2_add_f32(b: RtBuffer, i: vec2<u32>, v: f32) -> f32 {
    if rt_buf_check2(b, i) {
        let p = &rt_heap[b.offset + (i.y * b.width + i.x)];
        var old = atomicLoad(p);
        loop {
            let r = atomicCompareExchangeWeak(p, old, bitcast<u32>(bitcast<f32>(old) + v));
            if r.exchanged {
                return bitcast<f32>(old);
            }
            old = r.old_value;
        }
    }
    return f32();
}

fn rt_atomic2_add_u32(b: RtBuffer, i: vec2<u32>, v: u32) -> u32 {
    if rt_buf_check2(b, i) {
        let p = &rt_heap[b.offset + (i.y * b.width + i.x)];
        let old = atomicAdd(p, v);
        return old;
    }
    return u32();
}

fn rt_atomic_min_f32(b: RtBuffer, i: u32, v: f32) -> f32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        var old = atomicLoad(p);
        loop {
            let r = atomicCompareExchangeWeak(p, old, bitcast<u32>(select(bitcast<f32>(old), v, v < bitcast<f32>(old))));
            if r.exchanged {
                return bitcast<f32>(old);
            }
            old = r.old_value;
        }
    }
    return f32();
}

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rtp_receiver_cell(prd: ptr<function, Radiance>, hits: RtBuffer, energy: RtBuffer, nearest: RtBuffer, cells: u32) {
    let p: vec3<f32> = (rt_current_ray().origin + (rt_current_ray().direction * rt_t_hit()));
    let cell: vec2<f32> = (((p.xy * 0.5f) + vec2<f32>(0.5f)) * f32(cells));
    let at: vec2<u32> = vec2<u32>(rt_f2u(cell.x), rt_f2u(cell.y));
    let tmp = rt_atomic2_add_u32(hits, at, 1u);
    _ = tmp;
    let tmp_1 = rt_atomic2_add_f32(energy, at, (*prd).importance);
    _ = tmp_1;
    let tmp_2 = rt_atomic_min_f32(nearest, 0u, rt_t_hit());
    _ = tmp_2;
    (*prd).result = vec3<f32>(1.0);
}
