// ray_generation program `flags_and_claims` (atomic heap)

fn rt_atomic2_compare_exchange_u32(b: RtBuffer, i: vec2<u32>, current: u32, v: u32) -> u32 {
    if rt_buf_check2(b, i) {
        let p = &rt_heap[b.offset + (i.y * b.width + i.x)];
        loop {
            let r = atomicCompareExchangeWeak(p, current, v);
            if r.exchanged || r.old_value != current {
                let old = r.old_value;
                return old;
            }
        }
    }
    return u32();
}

fn rt_atomic_and_u32(b: RtBuffer, i: u32, v: u32) -> u32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        let old = atomicAnd(p, v);
        return old;
    }
    return u32();
}

fn rt_atomic_exchange_u32(b: RtBuffer, i: u32, v: u32) -> u32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        let old = atomicExchange(p, v);
        return old;
    }
    return u32();
}

fn rt_atomic_max_i32(b: RtBuffer, i: u32, v: i32) -> i32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        var old = atomicLoad(p);
        loop {
            let r = atomicCompareExchangeWeak(p, old, bitcast<u32>(select(bitcast<i32>(old), v, v > bitcast<i32>(old))));
            if r.exchanged {
                return bitcast<i32>(old);
            }
            old = r.old_value;
        }
    }
    return i32();
}

fn rt_atomic_min_i32(b: RtBuffer, i: u32, v: i32) -> i32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        var old = atomicLoad(p);
        loop {
            let r = atomicCompareExchangeWeak(p, old, bitcast<u32>(select(bitcast<i32>(old), v, v < bitcast<i32>(old))));
            if r.exchanged {
                return bitcast<i32>(old);
            }
            old = r.old_value;
        }
    }
    return i32();
}

fn rt_atomic_or_u32(b: RtBuffer, i: u32, v: u32) -> u32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        let old = atomicOr(p, v);
        return old;
    }
    return u32();
}

fn rt_atomic_sub_i32(b: RtBuffer, i: u32, v: i32) -> i32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        let old = atomicSub(p, bitcast<u32>(v));
        return bitcast<i32>(old);
    }
    return i32();
}

fn rt_atomic_xor_u32(b: RtBuffer, i: u32, v: u32) -> u32 {
    if rt_buf_check(b, i) {
        let p = &rt_heap[b.offset + i];
        let old = atomicXor(p, v);
        return old;
    }
    return u32();
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

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtp_flags_and_claims(signed: RtBuffer, bits: RtBuffer, owners: RtBuffer) {
    var bits_1 = bits;
    let i: vec2<u32> = rt_launch_index();
    let v: i32 = (i32(i.x) - i32(i.y));
    let tmp = rt_atomic_min_i32(signed, 0u, v);
    let lowest: i32 = tmp;
    let tmp_1 = rt_atomic_max_i32(signed, 1u, v);
    _ = tmp_1;
    let tmp_2 = rt_atomic_sub_i32(signed, 2u, v);
    _ = tmp_2;
    let tmp_3 = rt_atomic_or_u32(bits_1, 0u, (1u << (i.x % 32u)));
    _ = tmp_3;
    let tmp_4 = rt_atomic_and_u32(bits_1, 1u, ~(1u << (i.y % 32u)));
    _ = tmp_4;
    let tmp_5 = rt_atomic_xor_u32(bits_1, 2u, i.x);
    _ = tmp_5;
    let tmp_6 = rt_atomic_exchange_u32(bits_1, 4u, i.y);
    let tmp_7 = 3u;
    rt_bufstore_u32(bits_1, tmp_7, (tmp_6 + u32(lowest)));
    let tmp_8 = rt_atomic2_compare_exchange_u32(owners, (i / 8u), 0u, (i.x + 1u));
    _ = tmp_8;
}
