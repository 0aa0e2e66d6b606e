// ray_generation program `ops_arith`

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

fn rtp_ops_arith(a: f32, b: f32, n: i32, m: u32, out_f: RtBuffer, out_i: RtBuffer, out_u: RtBuffer) {
    let slot: u32 = rt_launch_index().x;
    let sum: f32 = (a + b);
    let diff: f32 = (a - b);
    let prod: f32 = (a * b);
    let quot: f32 = (a / b);
    let rem: f32 = rt_fmod(a, b);
    let neg: f32 = -a;
    var acc: f32 = sum;
    acc += diff;
    acc -= prod;
    acc *= 0.5f;
    acc /= (quot + 2.0f);
    acc = rt_fmod(acc, 7.0f);
    rt_bufstore_f32(out_f, slot, ((acc + (rem * neg)) - ((a - b) / (a + b))));
    var k: i32 = ((n * 3i) - 7i);
    k += (n / 2i);
    k -= (n % 3i);
    k *= -2i;
    k /= 3i;
    k %= 5i;
    var tmp: i32;
    if (n > 0i) {
        tmp = n;
    } else {
        tmp = -n;
    }
    let magnitude: i32 = max(1i, tmp);
    rt_bufstore_i32(out_i, slot, (((-k + ((n - 1i) * (n + 1i))) - -n) + magnitude));
    var w: u32 = (m + 1u);
    w *= 2u;
    w -= 1u;
    w /= 3u;
    w %= 100u;
    w += (m % 7u);
    rt_bufstore_u32(out_u, slot, ((w * 3u) + 10u));
}
