// ray_generation program `int_division`

fn rt_bufload_vec4i(b: RtBuffer, i: u32) -> vec4<i32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4i(b.offset + i * 4u);
    }
    return vec4<i32>();
}

fn rt_bufstore_vec4i(b: RtBuffer, i: u32, v: vec4<i32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4i(b.offset + i * 4u, v);
    }
}

fn rt_div_euclid_i32(a: i32, b: i32) -> i32 {
    let d = rt_safe_divisor_i32(a, b);
    return a / d - select(i32(0), sign(d), a % d < i32(0));
}

fn rt_div_euclid_vec2i(a: vec2<i32>, b: vec2<i32>) -> vec2<i32> {
    let d = rt_safe_divisor_vec2i(a, b);
    return a / d - select(vec2<i32>(0), sign(d), a % d < vec2<i32>(0));
}

fn rt_div_euclid_vec3i(a: vec3<i32>, b: vec3<i32>) -> vec3<i32> {
    let d = rt_safe_divisor_vec3i(a, b);
    return a / d - select(vec3<i32>(0), sign(d), a % d < vec3<i32>(0));
}

fn rt_div_u32(a: u32, b: u32) -> u32 {
    return a / select(b, u32(1), b == u32(0));
}

fn rt_div_vec2u(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    return a / select(b, vec2<u32>(1), b == vec2<u32>(0));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3i(w: u32) -> vec3<i32> {
    return vec3<i32>(rt_load_i32(w + 0u), rt_load_i32(w + 1u), rt_load_i32(w + 2u));
}

fn rt_load_vec4i(w: u32) -> vec4<i32> {
    return vec4<i32>(rt_load_i32(w + 0u), rt_load_i32(w + 1u), rt_load_i32(w + 2u), rt_load_i32(w + 3u));
}

fn rt_rem_euclid_i32(a: i32, b: i32) -> i32 {
    let d = rt_safe_divisor_i32(a, b);
    let r = a % d;
    return select(r, select(r + d, r - d, d < i32(0)), r < i32(0));
}

fn rt_rem_euclid_vec3i(a: vec3<i32>, b: vec3<i32>) -> vec3<i32> {
    let d = rt_safe_divisor_vec3i(a, b);
    let r = a % d;
    return select(r, select(r + d, r - d, d < vec3<i32>(0)), r < vec3<i32>(0));
}

fn rt_rem_u32(a: u32, b: u32) -> u32 {
    return a % select(b, u32(1), b == u32(0));
}

fn rt_safe_divisor_i32(a: i32, b: i32) -> i32 {
    return select(b, i32(1), (b == i32(0)) | ((a == i32(-2147483648)) & (b == i32(-1))));
}

fn rt_safe_divisor_vec2i(a: vec2<i32>, b: vec2<i32>) -> vec2<i32> {
    return select(b, vec2<i32>(1), (b == vec2<i32>(0)) | ((a == vec2<i32>(-2147483648)) & (b == vec2<i32>(-1))));
}

fn rt_safe_divisor_vec3i(a: vec3<i32>, b: vec3<i32>) -> vec3<i32> {
    return select(b, vec3<i32>(1), (b == vec3<i32>(0)) | ((a == vec3<i32>(-2147483648)) & (b == vec3<i32>(-1))));
}

fn rt_safe_divisor_vec4i(a: vec4<i32>, b: vec4<i32>) -> vec4<i32> {
    return select(b, vec4<i32>(1), (b == vec4<i32>(0)) | ((a == vec4<i32>(-2147483648)) & (b == vec4<i32>(-1))));
}

fn rt_saturating_div_i32(a: i32, b: i32) -> i32 {
    return select(a / rt_safe_divisor_i32(a, b), i32(2147483647), (a == i32(-2147483648)) & (b == i32(-1)));
}

fn rt_saturating_div_vec3i(a: vec3<i32>, b: vec3<i32>) -> vec3<i32> {
    return select(a / rt_safe_divisor_vec3i(a, b), vec3<i32>(2147483647), (a == vec3<i32>(-2147483648)) & (b == vec3<i32>(-1)));
}

fn rt_store_i32(w: u32, v: i32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_vec4i(w: u32, v: vec4<i32>) {
    rt_store_i32(w + 0u, v[0]);
    rt_store_i32(w + 1u, v[1]);
    rt_store_i32(w + 2u, v[2]);
    rt_store_i32(w + 3u, v[3]);
}

fn rt_wrapping_div_i32(a: i32, b: i32) -> i32 {
    return a / rt_safe_divisor_i32(a, b);
}

fn rt_wrapping_div_vec4i(a: vec4<i32>, b: vec4<i32>) -> vec4<i32> {
    return a / rt_safe_divisor_vec4i(a, b);
}

fn rtp_int_division(a: i32, b: u32, v: vec3<i32>, out: RtBuffer) {
    var out_1 = out;
    let q: i32 = (((rt_div_euclid_i32(a, -3i) + rt_rem_euclid_i32(a, 0i)) + rt_wrapping_div_i32(i32(-2147483648), -1i)) + rt_saturating_div_i32(a, a));
    let u: u32 = (((rt_div_u32(b, 0u) + rt_rem_u32(7u, b)) + rt_div_u32(b, 2u)) + rt_div_u32(b, b));
    let tmp = vec3<i32>(1i);
    let w: vec3<i32> = ((rt_div_euclid_vec3i(v, vec3<i32>(0i)) + rt_rem_euclid_vec3i(v, vec3<i32>(2i, -2i, 0i))) + rt_saturating_div_vec3i(vec3<i32>(i32(-2147483648)), -tmp));
    let x: vec2<u32> = (rt_div_vec2u(vec2<u32>(b, 9u), vec2<u32>(0u)) + rt_div_vec2u(vec2<u32>(b), vec2<u32>(3u, 0u)));
    let y: vec4<i32> = (rt_wrapping_div_vec4i(vec4<i32>(a, 1i, 2i, 3i), vec4<i32>(a)) + vec4<i32>(vec3<i32>(rt_div_euclid_vec2i(vec2<i32>(a, 5i), vec2<i32>(0i, -2i)), 0i), 1i));
    let tmp_1 = 0u;
    rt_bufstore_vec4i(out_1, tmp_1, (y + vec4<i32>(w, ((q + i32(u)) + i32(x.x)))));
}
