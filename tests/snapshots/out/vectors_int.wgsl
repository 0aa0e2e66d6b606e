// ray_generation program `vectors_int`

fn rt_bufload2_vec4f(b: RtBuffer, i: vec2<u32>) -> vec4<f32> {
    if rt_buf_check2(b, i) {
        return rt_load_vec4f(b.offset + (i.y * b.width + i.x) * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore2_vec4f(b: RtBuffer, i: vec2<u32>, v: vec4<f32>) {
    if rt_buf_check2(b, i) {
        rt_store_vec4f(b.offset + (i.y * b.width + i.x) * 4u, v);
    }
}

fn rt_f2i2(x: vec2<f32>) -> vec2<i32> {
    return select(select(vec2<i32>(x), vec2<i32>(2147483647i), x >= vec2<f32>(2147483648.0)), vec2<i32>(0), (bitcast<vec2<u32>>(x) & vec2<u32>(0x7fffffffu)) > vec2<u32>(0x7f800000u));
}

fn rt_f2u2(x: vec2<f32>) -> vec2<u32> {
    return select(select(vec2<u32>(x), vec2<u32>(4294967295u), x >= vec2<f32>(4294967296.0)), vec2<u32>(0), (bitcast<vec2<u32>>(x) & vec2<u32>(0x7fffffffu)) > vec2<u32>(0x7f800000u));
}

fn rt_f2u3(x: vec3<f32>) -> vec3<u32> {
    return select(select(vec3<u32>(x), vec3<u32>(4294967295u), x >= vec3<f32>(4294967296.0)), vec3<u32>(0), (bitcast<vec3<u32>>(x) & vec3<u32>(0x7fffffffu)) > vec3<u32>(0x7f800000u));
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

fn rt_load_vec2i(w: u32) -> vec2<i32> {
    return vec2<i32>(rt_load_i32(w + 0u), rt_load_i32(w + 1u));
}

fn rt_load_vec2u(w: u32) -> vec2<u32> {
    return vec2<u32>(rt_load_u32(w + 0u), rt_load_u32(w + 1u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4f(w: u32, v: vec4<f32>) {
    rt_store_f32(w + 0u, v[0]);
    rt_store_f32(w + 1u, v[1]);
    rt_store_f32(w + 2u, v[2]);
    rt_store_f32(w + 3u, v[3]);
}

fn rtp_vectors_int(tile: vec2<u32>, offset: vec2<i32>, out: RtBuffer) {
    var out_1 = out;
    let idx: vec2<u32> = rt_launch_index();
    let dim: vec2<u32> = rt_launch_dim();
    let tile_id: vec2<u32> = (idx / tile);
    let in_tile: vec2<u32> = (idx % tile);
    let checker: u32 = ((tile_id.x + tile_id.y) & 1u);
    let centered: vec2<i32> = ((vec2<i32>(idx) - vec2<i32>((dim / 2u))) + offset);
    let dist: vec2<i32> = clamp(min(max(abs(centered), vec2<i32>(1i)), vec2<i32>(1000i, 1000i)), vec2<i32>(0i), vec2<i32>(512i));
    let sgn: vec2<i32> = (((sign(centered) * vec2<i32>(-1i)) + vec2<i32>(1i, 0i)) - vec2<i32>(0i, 1i));
    let mixed: vec2<u32> = (((idx << vec2<u32>(1u)) ^ (dim >> vec2<u32>(2u))) | (vec2<u32>(1u, 2u) & ~vec2<u32>(0u)));
    let manhattan: i32 = ((((dist.x + dist.y) + dot(dist, vec2<i32>(1i, -1i))) + min(sgn.x, sgn.y)) + max(sgn.x, sgn.y));
    let tmp = vec3<u32>(1u, 2u, 3u);
    let bits: u32 = (((((mixed.x * mixed.y) + max(mixed.x, mixed.y)) + (tmp.x + tmp.y + tmp.z)) + vec2<u32>(1u, 0u).x) + vec2<u32>(0u, 1u).y);
    let tmp_1 = vec3<i32>(1i, 2i, 3i);
    let volume: vec3<i32> = (((tmp_1 * 2i) + 1i) - vec3<i32>(0i, 0i, 1i));
    let uv: vec2<f32> = ((vec2<f32>(idx) + 0.5f) / vec2<f32>(dim));
    var back: vec2<u32> = ((rt_f2u2(uv) + vec2<u32>(rt_f2i2((-uv)))) + rt_f2u3(vec3<f32>(volume)).xy);
    back <<= vec2<u32>(2u);
    back = (back >> vec2<u32>(vec2<i32>(1i, 0i)));
    back &= vec2<u32>(65535u);
    back |= vec2<u32>(1u, 0u);
    back ^= in_tile;
    var signed: vec3<i32> = (volume >> vec3<u32>(1u));
    signed = (signed << vec3<u32>(0u, 1u, 2u));
    signed ^= vec3<i32>(-1i);
    let corner: vec4<u32> = (vec4<u32>(in_tile.x, in_tile.y, checker, u32(signed.y)) + vec4<u32>(0u, 0u, 0u, 1u));
    let color: vec4<f32> = ((vec4<f32>(uv.x, uv.y, f32(checker), 1.0f) * (f32(manhattan) / 512.0f)) + (vec4<f32>(corner) * 0.01f));
    let tmp_2 = idx;
    rt_bufstore2_vec4f(out_1, tmp_2, (color + vec4<f32>((f32((bits + back.x)) * 1e-6f))));
}
