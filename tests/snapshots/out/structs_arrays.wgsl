// miss program `structs_arrays`

struct Ramp {
    stops: array<RampStop, 3>,
    weights: array<f32, 4>,
    count: u32,
}

struct RampSample {
    color: vec3<f32>,
    ramp: Ramp,
    hits: array<u32, 4>,
}

struct RampStop {
    at: f32,
    color: vec3<f32>,
}

fn rt_f2u(x: f32) -> u32 {
    return select(select(u32(x), u32(4294967295u), x >= f32(4294967296.0)), u32(0), (bitcast<u32>(x) & u32(0x7fffffffu)) > u32(0x7f800000u));
}

fn rt_load_Ramp(w: u32) -> Ramp {
    return Ramp(rt_load_arr3_RampStop(w + 0u), rt_load_arr4_f32(w + 12u), rt_load_u32(w + 16u));
}

fn rt_load_RampStop(w: u32) -> RampStop {
    return RampStop(rt_load_f32(w + 0u), rt_load_vec3f(w + 1u));
}

fn rt_load_arr3_RampStop(w: u32) -> array<RampStop, 3> {
    var a: array<RampStop, 3>;
    for (var i = 0u; i < 3u; i++) {
        a[i] = rt_load_RampStop(w + i * 4u);
    }
    return a;
}

fn rt_load_arr4_f32(w: u32) -> array<f32, 4> {
    var a: array<f32, 4>;
    for (var i = 0u; i < 4u; i++) {
        a[i] = rt_load_f32(w + i * 1u);
    }
    return a;
}

fn rt_load_f32(w: u32) -> f32 {
    return bitcast<f32>(rt_hw(w));
}

fn rt_load_u32(w: u32) -> u32 {
    return rt_hw(w);
}

fn rt_load_vec3f(w: u32) -> vec3<f32> {
    return vec3<f32>(rt_load_f32(w + 0u), rt_load_f32(w + 1u), rt_load_f32(w + 2u));
}

fn rtp_structs_arrays(prd: ptr<function, RampSample>, ramp: Ramp) {
    let t: f32 = ((rt_current_ray().direction.y * 0.5f) + 0.5f);
    var color: vec3<f32> = ramp.stops[0u].color;
    for (var i: u32 = 1u; i < 3u; i++) {
        let lo: RampStop = ramp.stops[(i - 1u)];
        let hi: RampStop = ramp.stops[i];
        if ((t >= lo.at) && (t < hi.at)) {
            let tmp = ((t - lo.at) / (hi.at - lo.at));
            color = (lo.color * (1.0 - tmp) + hi.color * tmp);
        }
    }
    var weights: array<f32, 4> = array<f32, 4>(0.0f, 0.0f, 0.0f, 0.0f);
    var squares: array<u32, 4> = array<u32, 4>(1u, 4u, 9u, 16u);
    var total: f32 = 0.0f;
    for (var i_1: u32 = 0u; i_1 < 4u; i_1++) {
        weights[i_1] = (ramp.weights[i_1] * f32(squares[i_1]));
        total += weights[i_1];
    }
    let bucket: u32 = min(rt_f2u((t * 4.0f)), 3u);
    (*prd).hits[bucket] += 1u;
    (*prd).color = (color * total);
    let first: RampStop = RampStop(0.0f, vec3<f32>(0.0));
    (*prd).ramp = Ramp(array<RampStop, 3>(first, RampStop(t, color), ramp.stops[2u]), weights, (ramp.count + 1u));
    (*prd).ramp.stops[1u].color.y = t;
    (*prd).ramp.weights[bucket] *= 2.0f;
    var copy: RampStop = (*prd).ramp.stops[2u];
    copy.at += 1.0f;
    var blank: RampStop = RampStop();
    if (copy.at > 1.0f) {
        blank.at = copy.at;
    }
    (*prd).ramp.stops[0u] = blank;
}
