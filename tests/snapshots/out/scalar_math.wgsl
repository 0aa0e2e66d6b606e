// ray_generation program `scalar_math`

fn rt_bufstore_f32(b: RtBuffer, i: u32, v: f32) {
    if rt_buf_check(b, i) {
        rt_store_f32(b.offset + i * 1u, v);
    }
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_powi(x: f32, n: i32) -> f32 {
    var base = x;
    var e = n;
    var r = 1.0f;
    loop {
        if (e & 1i) != 0i {
            r *= base;
        }
        e /= 2i;
        if e == 0i {
            break;
        }
        base *= base;
    }
    return select(r, 1.0f / r, n < 0i);
}

fn rt_store_f32(w: u32, v: f32) {
    rt_hw_set(w, bitcast<u32>(v));
}

fn rtp_scalar_math(x: f32, y: f32, out: RtBuffer) {
    let slot: u32 = rt_launch_index().x;
    let roots: f32 = ((((sqrt(abs(x)) + (1.0f / x)) + pow(x, 1.5f)) + rt_powi((x - 2.0f), 3i)) + rt_powi(x, -2i));
    let exps: f32 = (((((exp(x) + exp2(x)) + log(abs(y))) + log2(abs(y))) + radians(x)) + degrees(y));
    let trig: f32 = ((((((sin(x) * cos(y)) + tan(x)) + asin(clamp(x, -1.0f, 1.0f))) + acos(clamp(y, -1.0f, 1.0f))) + atan(x)) + atan2(y, x));
    let hyper: f32 = (((((sinh(x) + cosh(x)) + tanh(x)) + asinh(x)) + acosh((abs(y) + 1.0f))) + atanh(tanh((x * 0.5f))));
    let rounding: f32 = ((((((floor(x) + ceil(x)) + (trunc(x) + sign(x) * step(0.5f, abs(x - trunc(x))))) + trunc(x)) + (x - trunc(x))) + select(1.0f, -1.0f, (bitcast<u32>(x) & 0x80000000u) != 0u)) + round(x));
    let misc: f32 = (((((fma(x, y, 1.0f) + length(vec2<f32>(x, y))) + min(x, y)) + max(x, y)) + max(x, 0.0f)) + min(y, 3.1415927f));
    let consts: f32 = (((((6.2831855f * 0.31830987f) + (2.7182817f * 0.6931472f)) + (1.4142135f * 0.7853982f)) + 1.0471976f) + 1.1920929e-7f);
    var total: f32 = ((((((roots + exps) + trig) + hyper) + rounding) + misc) + consts);
    if (((total != total) || (abs(total) > 0x1.fffffep+127f)) || !(abs(total) <= 0x1.fffffep+127f)) {
        total = min(0x1.fffffep+127f, (1.1754944e-38f + abs(-0x1.fffffep+127f)));
    }
    rt_bufstore_f32(out, slot, total);
}
