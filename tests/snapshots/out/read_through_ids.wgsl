// ray_generation program `read_through_ids`

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

fn rt_idlen_u32(id: u32) -> u32 {
    if rt_bufid_ok(id, 99841201u, false) {
        return rt_bufid(id).len;
    }
    return 0u;
}

fn rt_idlenw_u32(id: u32) -> u32 {
    if rt_bufid_ok(id, 99841201u, true) {
        return rt_bufid(id).len;
    }
    return 0u;
}

fn rt_idload_u32(id: u32, i: u32) -> u32 {
    if rt_bufid_ok(id, 99841201u, false) {
        return rt_bufload_u32(rt_bufid(id), i);
    }
    return u32();
}

fn rt_idstore_u32(id: u32, i: u32, v: u32) {
    if rt_bufid_ok(id, 99841201u, true) {
        rt_bufstore_u32(rt_bufid(id), i, v);
    }
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtp_read_through_ids(first: u32, ids: RtBuffer, sink: u32, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let b: u32 = rt_bufload_u32(ids, (i % ids.len));
    var n: u32 = (rt_idlen_u32(b) + rt_idload_u32(b, i));
    if ((b == first) || (b == 0u)) {
        n += rt_idload_u32(i, 0u);
    }
    rt_idstore_u32(sink, i, (n + rt_idlenw_u32(sink)));
    let tmp = i;
    rt_bufstore_u32(out_1, tmp, n);
}
