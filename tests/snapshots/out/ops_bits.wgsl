// ray_generation program `ops_bits`

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

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_store_i32(w: u32, v: i32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rtf_pcg_hash(v: u32) -> u32 {
    let state: u32 = ((v * 747796405u) + 2891336453u);
    let word: u32 = (((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u);
    return ((word >> 22u) ^ word);
}

fn rtp_ops_bits(seed: u32, signed_seed: i32, shift: i32, out_u: RtBuffer, out_i: RtBuffer) {
    let idx: vec2<u32> = rt_launch_index();
    let pixel: u32 = ((idx.y * rt_launch_dim().x) + idx.x);
    let h: u32 = rtf_pcg_hash((pixel ^ seed));
    var bits: u32 = (h & 65535u);
    let tmp = 1u;
    bits |= (tmp << 31u);
    bits ^= seed;
    bits &= ~240u;
    bits <<= 3u;
    bits >>= 1u;
    bits <<= u32(shift);
    let packed: u32 = (((h >> 24u) | ((h & 255u) << 8u)) | (~h & 16711680u));
    let count: u32 = ((countOneBits(bits) + countLeadingZeros(packed)) + countTrailingZeros(h));
    rt_bufstore_u32(out_u, pixel, ((bits ^ reverseBits(packed)) ^ (count - 1u)));
    var s: i32 = signed_seed;
    s >>= 2u;
    s <<= u32(shift);
    s |= -16i;
    s &= ~(1i << 3u);
    s ^= 85i;
    let t: i32 = (((s >> u32(shift)) & (s << 1u)) | (~s ^ (s >> 31u)));
    let ones: i32 = ((i32(u32(countOneBits(s))) - i32(u32(countLeadingZeros(s)))) + i32(u32(countTrailingZeros(s))));
    rt_bufstore_i32(out_i, pixel, (abs(((t + ones) * 3i)) + sign(reverseBits(s))));
}
