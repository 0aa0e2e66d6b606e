// miss program `vectors`

struct Radiance {
    result: vec3<f32>,
    importance: f32,
    depth: i32,
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

fn rt_fmod3(x: vec3<f32>, y: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(rt_fmod(x.x, y.x), rt_fmod(x.y, y.y), rt_fmod(x.z, y.z));
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_vectors(prd: ptr<function, Radiance>, a: vec3<f32>, b: vec3<f32>, t: f32) {
    let d: vec3<f32> = rt_current_ray().direction;
    let n: vec3<f32> = normalize(cross(a, b));
    let cos_: f32 = dot(d, n);
    let len: f32 = ((length(a) + dot(b, b)) + inverseSqrt(dot(a, a)));
    let dist: f32 = (distance(a, b) + dot(a - b, a - b));
    let tmp = (a - b);
    let safe: vec3<f32> = select(vec3<f32>(), tmp * inverseSqrt(select(1.0, dot(tmp, tmp), dot(tmp, tmp) > 0.0)), dot(tmp, tmp) > 0.0);
    let per: vec3<f32> = clamp(max(min(abs(a), b), vec3<f32>(0.1f)), vec3<f32>(0.0), vec3<f32>(1.0));
    let blend: vec3<f32> = (a * (1.0 - t) + b * t);
    let curve: vec3<f32> = (((((pow(abs(a), vec3<f32>(2.2f)) + sqrt(abs(b))) + exp(a)) + log(abs(b))) + exp2(a)) + log2(abs(b)));
    let waves: vec3<f32> = (((sin(a) * cos(b)) + (vec3<f32>(1.0) / a)) + fma(a, b, vec3<f32>(1.0)));
    let rounded: vec3<f32> = ((((((floor(a) + ceil(a)) + (trunc(a) + sign(a) * step(vec3<f32>(0.5), abs(a - trunc(a))))) + trunc(a)) + (a - trunc(a))) + fract(a)) + select(vec3<f32>(1.0), vec3<f32>(-1.0), (bitcast<vec3<u32>>(a) & vec3<u32>(0x80000000u)) != vec3<u32>(0u)));
    let mirrored: vec3<f32> = (reflect(d, n) + refract(d, n, (1.0f / 1.5f)));
    let h: vec4<f32> = vec4<f32>(a, 1.0f);
    let back: vec3<f32> = (h.xyz + vec4<f32>(1.0f, 2.0f, 3.0f, 4.0f).xyz);
    let uv: vec2<f32> = ((d.xy + d.zx) + vec2<f32>(t, t).yx);
    let wide: vec4<f32> = ((d.xyzx + d.zzzz) + vec4<f32>(0.0f, 1.0f, 2.0f, 3.0f).wzyx);
    let reduced: f32 = (((((a.x + a.y + a.z) + (a.x * a.y * a.z)) + min(min(a.x, a.y), a.z)) + max(max(b.x, b.y), b.z)) + max(max(max(wide.x, wide.y), wide.z), wide.w));
    var c: vec3<f32> = (((((2.0f * per) + (blend / 3.0f)) - (curve * 0.5f)) + rt_fmod3(waves, vec3<f32>(4.0f))) - -rounded);
    c.x = (c[1u] + c.y);
    c[2u] = (uv.x + uv[1u]);
    c += mirrored;
    c -= vec3<f32>(1.0, 0.0, 0.0);
    c *= (safe + back);
    c /= vec3<f32>((((len + dist) + cos_) + reduced));
    c *= 0.5f;
    (*prd).result = ((((((c + (vec3<f32>(0.0, 1.0, 0.0) * h.w)) + vec3<f32>(0.0, 0.0, -1.0)) + vec3<f32>(-1.0)) + (vec3<f32>(0.0, 0.0, 1.0) * vec4<f32>(0.0, 0.0, 0.0, 1.0).w)) + vec3<f32>(-1.0, 0.0, 0.0)) + vec3<f32>(0.0, -1.0, 0.0));
}
