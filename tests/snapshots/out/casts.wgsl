// ray_generation program `casts`

fn rt_bufload_f32(b: RtBuffer, i: u32) -> f32 {
    if rt_buf_check(b, i) {
        return rt_load_f32(b.offset + i * 1u);
    }
    return f32();
}

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_i32(b: RtBuffer, i: u32, v: i32) {
    if rt_buf_check(b, i) {
        rt_store_i32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
}

fn rt_f2i(x: f32) -> i32 {
    return select(select(i32(x), i32(2147483647i), x >= f32(2147483648.0)), i32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_load_bool(w: u32) -> bool {
    return rt_hw(w) != 0u;
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

fn rt_store_i32(w: u32, v: i32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtp_casts(f: f32, i: i32, u: u32, flag: bool, table: RtBuffer, out_f: RtBuffer, out_i: RtBuffer, out_u: RtBuffer) {
    let slot: u32 = rt_launch_index().x;
    let from_f_i: i32 = rt_f2i(f);
    let from_f_u: u32 = rt_f2u(f);
    let from_f_z: u32 = rt_f2u(f);
    let from_i_f: f32 = f32(i);
    let from_i_u: u32 = u32(i);
    let from_i_z: u32 = u32(i);
    let from_u_f: f32 = f32(u);
    let from_u_i: i32 = i32(u);
    let from_u_z: u32 = u;
    let from_z_f: f32 = f32(from_i_z);
    let from_z_i: i32 = i32(from_u_z);
    let from_z_u: u32 = from_f_z;
    let from_b_i: i32 = i32(flag);
    let from_b_u: u32 = u32(flag);
    let from_b_z: u32 = u32(flag);
    var weights: array<f32, 4> = array<f32, 4>(0.5f, 0.25f, 0.125f, 0.0625f);
    let picked: f32 = ((weights[(u % 4u)] + weights[from_b_z]) + weights[(from_u_z % 4u)]);
    let sum: f32 = (((((from_i_f + from_u_f) + from_z_f) + picked) + rt_bufload_f32(table, from_z_u)) + f32((slot / 2u)));
    rt_bufstore_f32(out_f, slot, sum);
    rt_bufstore_i32(out_i, slot, (((((from_f_i + from_u_i) + from_z_i) + from_b_i) + rt_f2i((sum * 0.5f))) + i32((u >> 1u))));
    rt_bufstore_u32(out_u, slot, ((((from_f_u + from_i_u) + from_b_u) + (from_i_z + from_f_z)) + rt_f2u((-f))));
}
