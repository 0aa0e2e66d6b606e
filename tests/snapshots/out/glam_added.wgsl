// ray_generation program `glam_added`

struct rt_tuple_vec3f_f32_ {
    f0: vec3<f32>,
    f1: f32,
}

struct rt_tuple_vec3f_vec3f_ {
    f0: vec3<f32>,
    f1: vec3<f32>,
}

fn rt_acos_approx(v: f32) -> f32 {
    let x = abs(v);
    let root = sqrt(max(1.0f - x, 0.0f));
    let p = ((((((-0.0012624911f * x + 0.00667009f) * x - 0.017088126f) * x + 0.03089188f) * x - 0.050174303f) * x + 0.08897899f) * x - 0.2145988f) * x + 1.5707963f;
    let r = p * root;
    return select(3.1415927f - r, r, v >= 0.0f);
}

fn rt_angle_to2(a: vec2<f32>, b: vec2<f32>) -> f32 {
    let angle = rt_acos_approx(dot(a, b) / sqrt(dot(a, a) * dot(b, b)));
    let perp_dot = a.x * b.y - a.y * b.x;
    return angle * select(1.0f, -1.0f, (bitcast<u32>(perp_dot) & 0x80000000u) != 0u);
}

fn rt_any_orthonormal_pair(v: vec3<f32>) -> rt_tuple_vec3f_vec3f_ {
    let sign = select(1.0f, -1.0f, (bitcast<u32>(v.z) & 0x80000000u) != 0u);
    let a = -1.0f / (sign + v.z);
    let b = v.x * v.y * a;
    return rt_tuple_vec3f_vec3f_(vec3<f32>(1.0f + sign * v.x * v.x * a, sign * b, -sign * v.x), vec3<f32>(b, sign + v.y * v.y * a, -v.y));
}

fn rt_bufload_vec4f(b: RtBuffer, i: u32) -> vec4<f32> {
    if rt_buf_check(b, i) {
        return rt_load_vec4f(b.offset + i * 4u);
    }
    return vec4<f32>();
}

fn rt_bufstore_vec4f(b: RtBuffer, i: u32, v: vec4<f32>) {
    if rt_buf_check(b, i) {
        rt_store_vec4f(b.offset + i * 4u, v);
    }
}

fn rt_div_euclid(a: f32, b: f32) -> f32 {
    let q = trunc(a / b);
    if rt_fmod(a, b) < 0.0f {
        return select(q + 1.0f, q - 1.0f, b > 0.0f);
    }
    return q;
}

fn rt_fmod(x: f32, y: f32) -> f32 {
    let ux = bitcast<u32>(x);
    let uy = bitcast<u32>(y);
    var ex = i32((ux >> 23u) & 0xffu);
    var ey = i32((uy >> 23u) & 0xffu);
    let sx = ux & 0x80000000u;
    if (uy << 1u) == 0u || ex == 0xff || (uy & 0x7fffffffu) > 0x7f800000u {
        return x % y;
    }
    if (ux << 1u) <= (uy << 1u) {
        if (ux << 1u) == (uy << 1u) {
            return bitcast<f32>(sx);
        }
        return x;
    }
    var mx = (ux & 0x007fffffu) | 0x00800000u;
    if ex == 0 {
        var i = ux << 9u;
        while (i >> 31u) == 0u {
            ex -= 1;
            i <<= 1u;
        }
        mx = ux << u32(1 - ex);
    }
    var my = (uy & 0x007fffffu) | 0x00800000u;
    if ey == 0 {
        var i = uy << 9u;
        while (i >> 31u) == 0u {
            ey -= 1;
            i <<= 1u;
        }
        my = uy << u32(1 - ey);
    }
    loop {
        let i = mx - my;
        if (i >> 31u) == 0u {
            if i == 0u {
                return bitcast<f32>(sx);
            }
            mx = i;
        }
        if ex <= ey {
            break;
        }
        mx <<= 1u;
        ex -= 1;
    }
    while (mx >> 23u) == 0u {
        mx <<= 1u;
        ex -= 1;
    }
    if ex > 0 {
        mx = (mx - 0x00800000u) | (u32(ex) << 23u);
    } else {
        mx >>= u32(1 - ex);
    }
    return bitcast<f32>(mx | sx);
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rt_load_vec4f(w: u32) -> vec4<f32> {
    return vec4<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u), rt_load_f32(w + 3u));
}

fn rt_move_towards3(v: vec3<f32>, rhs: vec3<f32>, d: f32) -> vec3<f32> {
    let a = rhs - v;
    let len = length(a);
    if len <= d || len <= 1e-4f {
        return rhs;
    }
    return v + a / len * d;
}

fn rt_normalize_and_length3(v: vec3<f32>) -> rt_tuple_vec3f_f32_ {
    let length = length(v);
    let rcp = 1.0f / length;
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return rt_tuple_vec3f_f32_(v * rcp, length);
    }
    return rt_tuple_vec3f_f32_(vec3<f32>(1.0f, 0.0f, 0.0f), 0.0f);
}

fn rt_normalize_or3(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let rcp = 1.0f / length(v);
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        return v * rcp;
    }
    return fallback;
}

fn rt_rem_euclid(a: f32, b: f32) -> f32 {
    let r = rt_fmod(a, b);
    return select(r, r + abs(b), r < 0.0f);
}

fn rt_rotate_axis(v: vec3<f32>, axis: vec3<f32>, angle: f32) -> vec3<f32> {
    let s = sin(angle * 0.5f);
    let w = cos(angle * 0.5f);
    let b = axis * s;
    let b2 = dot(b, b);
    return v * (w * w - b2) + b * (dot(v, b) * 2.0f) + cross(b, v) * (w * 2.0f);
}

fn rt_rotate_towards3(v: vec3<f32>, rhs: vec3<f32>, max_angle: f32) -> vec3<f32> {
    let between = rt_acos_approx(dot(v, rhs) / sqrt(dot(v, v) * dot(rhs, rhs)));
    let angle = clamp(max_angle, between - 3.1415927f, between);
    let c = cross(v, rhs);
    let rcp = 1.0f / length(c);
    var axis = normalize(select(vec3<f32>(0.0f, v.z, -v.y), vec3<f32>(-v.z, 0.0f, v.x), abs(v.x) > abs(v.y)));
    if abs(rcp) <= 0x1.fffffep+127f && rcp > 0.0f {
        axis = c * rcp;
    }
    return rt_rotate_axis(v, axis, angle);
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

fn rtp_glam_added(a: vec3<f32>, b: vec3<f32>, k: i32, out: RtBuffer) {
    var out_1 = out;
    let i: u32 = rt_launch_index().x;
    let tuple: rt_tuple_vec3f_vec3f_ = rt_any_orthonormal_pair(normalize(b));
    let u: vec3<f32> = tuple.f0;
    let v: vec3<f32> = tuple.f1;
    let tuple_1: rt_tuple_vec3f_vec3f_ = rt_tuple_vec3f_vec3f_(sin(a), cos(a));
    let s: vec3<f32> = tuple_1.f0;
    let c: vec3<f32> = tuple_1.f1;
    let tuple_2: rt_tuple_vec3f_f32_ = rt_normalize_and_length3(a);
    let n: vec3<f32> = tuple_2.f0;
    let len: f32 = tuple_2.f1;
    let turned: vec3<f32> = ((rt_rotate_axis(a, vec3<f32>(0.0, 0.0, 1.0), 0.5f) + rt_rotate_towards3(a, b, 0.25f)) + vec3<f32>(a.x, a.y * cos(0.1f) - a.z * sin(0.1f), a.y * sin(0.1f) + a.z * cos(0.1f)));
    let tmp = vec3<f32>(1.0, 0.0, 0.0);
    let tmp_1 = vec3<f32>(0.0, 1.0, 0.0);
    let flat: f32 = ((rt_angle_to2(a.xy, b.xy) + rt_acos_approx(dot(tmp, tmp_1) / sqrt(dot(tmp, tmp) * dot(tmp_1, tmp_1)))) + atan2(dot(cross(a, b), vec3<f32>(0.0, 0.0, 1.0)), dot(a, b)));
    let moved: vec3<f32> = ((rt_move_towards3(a, b, 0.5f) + rt_normalize_or3(a, vec3<f32>(0.0, 1.0, 0.0))) + select(vec3<f32>(0.0f, a.z, -a.y), vec3<f32>(-a.z, 0.0f, a.x), abs(a.x) > abs(a.y)));
    let tmp_2 = vec3<f32>(2.0f);
    let e: vec3<f32> = (vec3<f32>(rt_rem_euclid(a.x, b.x), rt_rem_euclid(a.y, b.y), rt_rem_euclid(a.z, b.z)) + vec3<f32>(rt_div_euclid(a.x, tmp_2.x), rt_div_euclid(a.y, tmp_2.y), rt_div_euclid(a.z, tmp_2.z)));
    let ints: vec3<i32> = vec3<i32>(k, 2i, 3i);
    let tmp_3 = 5i;
    let tmp_4 = vec3<i32>(2147483647i);
    let sat: i32 = ((select((k * k), select(i32(-2147483648), 2147483647i, (k < 0i) == (k < 0i)), (((k != 0i) & ((k * k) / k != k)) | ((k == -1i) & (k == i32(-2147483648))))) + select((tmp_3 * 0i), select(i32(-2147483648), 2147483647i, (tmp_3 < 0i) == (0i < 0i)), (((tmp_3 != 0i) & ((tmp_3 * 0i) / tmp_3 != 0i)) | ((tmp_3 == -1i) & (0i == i32(-2147483648)))))) + select((ints + tmp_4), select(vec3<i32>(i32(-2147483648)), vec3<i32>(2147483647i), ints >= vec3<i32>(0i)), (((ints ^ (ints + tmp_4)) & (tmp_4 ^ (ints + tmp_4))) < vec3<i32>(0i))).x);
    let tmp_5 = vec3<i32>(1i);
    let tmp_6 = vec3<i32>(1i, 0i, 0i);
    let tmp_7 = vec3<i32>(tmp_5.y * tmp_6.z - tmp_6.y * tmp_5.z, tmp_5.z * tmp_6.x - tmp_6.z * tmp_5.x, tmp_5.x * tmp_6.y - tmp_6.x * tmp_5.y);
    let tmp_8 = vec3<i32>(ints.y * tmp_7.z - tmp_7.y * ints.z, ints.z * tmp_7.x - tmp_7.z * ints.x, ints.x * tmp_7.y - tmp_7.x * ints.y);
    let tmp_9 = vec3<i32>(0i);
    let geo: i32 = (dot(tmp_8, tmp_8) + i32((select(bitcast<u32>(ints.x) - bitcast<u32>(tmp_9.x), bitcast<u32>(tmp_9.x) - bitcast<u32>(ints.x), ints.x < tmp_9.x) + select(bitcast<u32>(ints.y) - bitcast<u32>(tmp_9.y), bitcast<u32>(tmp_9.y) - bitcast<u32>(ints.y), ints.y < tmp_9.y) + select(bitcast<u32>(ints.z) - bitcast<u32>(tmp_9.z), bitcast<u32>(tmp_9.z) - bitcast<u32>(ints.z), ints.z < tmp_9.z))));
    let tmp_10 = 7u;
    let pos: u32 = (((select(select(0u, 1u, a.y < a.x), 2u, a.z < min(a.x, a.y)) + select(select(0u, 1u, ints.y > ints.x), 2u, ints.z > max(ints.x, ints.y))) + (((bitcast<u32>(a.x) >> 31u) << 0u) | ((bitcast<u32>(a.y) >> 31u) << 1u) | ((bitcast<u32>(a.z) >> 31u) << 2u))) + select(tmp_10 - 9u, 0u, 9u > tmp_10));
    let tmp_11 = i;
    rt_bufstore_vec4f(out_1, tmp_11, vec4<f32>((((((((u + v) + s) + c) + (n * len)) + turned) + moved) + e), ((flat + f32((sat + geo))) + f32(pos))));
}
