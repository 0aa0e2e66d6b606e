// ray_generation program `bool_vectors`

fn rt_bufload_vec4u(b: RtBuffer, i: u32) -> vec4<u32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4u(b.offset + i * 4u);
    }
    return vec4<u32>();
}

fn rt_bufstore_vec4u(b: RtBuffer, i: u32, v: vec4<u32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4u(b.offset + i * 4u, v);
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

fn rt_load_vec2i(w: u32) -> vec2<i32> {
    return vec2<i32>(rt_load_i32(w + 0u), rt_load_i32(w + 1u));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_load_vec4u(w: u32) -> vec4<u32> {
    return vec4<u32>(rt_load_u32(w + 0u), rt_load_u32(w + 1u), rt_load_u32(w + 2u), rt_load_u32(w + 3u));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

fn rt_store_vec4u(w: u32, v: vec4<u32>) {
    rt_store_u32(w + 0u, v[0]);
    rt_store_u32(w + 1u, v[1]);
    rt_store_u32(w + 2u, v[2]);
    rt_store_u32(w + 3u, v[3]);
}

fn rtf_outside(p: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> vec3<bool> {
    return ((p < lo) | (p > hi));
}

fn rtp_bool_vectors(p: vec3<f32>, q: vec4<f32>, i: vec2<i32>, out: RtBuffer) {
    var out_1 = out;
    let away: vec3<bool> = rtf_outside(p, vec3<f32>(0.0), vec3<f32>(1.0));
    var m: vec3<bool> = (away != vec3<bool>(true, false, true));
    m &= (!((bitcast<vec3<u32>>(p) & vec3<u32>(0x7fffffffu)) > vec3<u32>(0x7f800000u)) & (abs(p) <= vec3<f32>(0x1.fffffep+127f)));
    let signs: vec4<bool> = (((bitcast<vec4<u32>>(q) & vec4<u32>(0x80000000u)) != vec4<u32>(0u)) | ((q == vec4<f32>(0.0)) & !vec4<bool>(false)));
    let c: vec3<f32> = select(-p, p, m);
    let k: vec2<i32> = select((i32(dot(select(vec2<u32>(0u), vec2<u32>(1u, 2u), (i < vec2<i32>(0i))), vec2<u32>(1u))) * vec2<i32>(1i)), i, ((i >= vec2<i32>(0i)) & vec2<bool>(true, true)));
    let u: bool = all((vec4<u32>(3u) != vec4<u32>(1u, 3u, 5u, 3u)) == vec4<bool>(true, false, true, false));
    let tmp = 0u;
    rt_bufstore_vec4u(out_1, tmp, vec4<u32>((dot(select(vec3<u32>(0u), vec3<u32>(1u, 2u, 4u), m), vec3<u32>(1u)) | (dot(select(vec4<u32>(0u), vec4<u32>(1u, 2u, 4u, 8u), signs), vec4<u32>(1u)) << 3u)), ((u32(any(away)) + u32(all(m))) + u32(u)), ((dot(select(vec2<u32>(0u), vec2<u32>(1u, 2u), (i <= k)), vec2<u32>(1u)) + dot(select(vec2<u32>(0u), vec2<u32>(1u, 2u), (i < k)), vec2<u32>(1u))) + dot(select(vec2<u32>(0u), vec2<u32>(1u, 2u), (i == k)), vec2<u32>(1u))), (dot(select(vec4<u32>(0u), vec4<u32>(1u, 2u, 4u, 8u), !(select(vec4<f32>(1.0), q, signs) == q)), vec4<u32>(1u)) + dot(select(vec3<u32>(0u), vec3<u32>(1u, 2u, 4u), (c > p)), vec3<u32>(1u)))));
}
