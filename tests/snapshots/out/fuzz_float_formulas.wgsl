// ray_generation program `fuzz_float_formulas`

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_bufstore_u32(b: RtBuffer, i: u32, v: u32) {
    if rt_buf_check(b, i) {
        rt_store_u32(b.offset + i * 1u, v);
    }
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

fn rt_load_i32(w: u32) -> i32 {
    return bitcast<i32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_rem_vec4(x: vec4<f32>, y: vec4<f32>) -> vec4<f32> {
    return x - floor(x / y) * y;
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rt_store_u32(w: u32, v: u32) {
    rt_hw_set(w, v);
}

const SLOTS: u32 = 8u;

fn rtp_fuzz_float_formulas(a: u32, b: i32, x: f32, out_u: RtBuffer, out_f: RtBuffer) {
    let slot: u32 = (rt_launch_index().x * SLOTS);
    let r4: vec4<f32> = rt_rem_vec4(vec4<f32>(x, -x, 5.5f, -5.5f), vec4<f32>(2.0f));
    let r3: vec3<f32> = rt_fmod3(vec3<f32>(x, -x, -5.5f), vec3<f32>(2.0f));
    rt_bufstore_f32(out_f, slot, r4.x);
    rt_bufstore_f32(out_f, (slot + 1u), r4.y);
    rt_bufstore_f32(out_f, (slot + 2u), r4.w);
    rt_bufstore_f32(out_f, (slot + 3u), r3.y);
    let t: f32 = f32((b & 1i));
    rt_bufstore_f32(out_f, (slot + 4u), (vec3<f32>(-3.5f) * (1.0 - t) + vec3<f32>(0.001f) * t).x);
    rt_bufstore_f32(out_f, (slot + 5u), (-3.5f * (1.0 - t) + 0.001f * t));
    rt_bufstore_f32(out_f, (slot + 6u), (select(0.0f, 1.0f, -4.0f >= x) - 0.001f));
    rt_bufstore_f32(out_f, (slot + 7u), (select(vec2<f32>(0.0), vec2<f32>(1.0), vec2<f32>(-4.0f, 4.0f) >= vec2<f32>(x)).y + 0.1f));
    rt_bufstore_u32(out_u, slot, a);
}
