//! Structs and fixed-size arrays: array literals and `[x; N]` repeats,
//! indexing (and assigning) with a loop variable, arrays of structs and
//! arrays inside structs, nested struct literals, field assignment through
//! the payload reference, `Default::default()` and struct copies.
use rt_std::prelude::*;

/// One stop of a colour ramp.
#[rt_struct]
pub struct RampStop {
    pub at: f32,
    pub color: Vec3,
}

/// A colour ramp with a fixed number of stops, and a histogram.
#[rt_struct]
pub struct Ramp {
    pub stops: [RampStop; 3],
    pub weights: [f32; 4],
    pub count: u32,
}

/// What a ramp lookup leaves in the payload.
#[rt_payload]
pub struct RampSample {
    pub color: Vec3,
    pub ramp: Ramp,
    pub hits: [u32; 4],
}

#[rt_program(miss)]
pub fn structs_arrays(prd: &mut RampSample, #[var] ramp: Ramp) {
    let t = current_ray().direction.y * 0.5 + 0.5;
    let mut color = ramp.stops[0].color;
    for i in 1..3 {
        let lo = ramp.stops[i - 1];
        let hi = ramp.stops[i];
        if t >= lo.at && t < hi.at {
            color = lo.color.lerp(hi.color, (t - lo.at) / (hi.at - lo.at));
        }
    }
    let mut weights = [0.0f32; 4];
    let squares = [1u32, 4, 9, 16];
    let mut total = 0.0;
    for i in 0..4 {
        weights[i] = ramp.weights[i] * squares[i] as f32;
        total += weights[i];
    }
    let bucket = ((t * 4.0) as usize).min(3);
    prd.hits[bucket] += 1;
    prd.color = color * total;
    let first = RampStop { at: 0.0, color: Vec3::ZERO };
    prd.ramp = Ramp { stops: [first, RampStop { color, at: t }, ramp.stops[2]], weights, count: ramp.count + 1 };
    prd.ramp.stops[1].color.y = t;
    prd.ramp.weights[bucket] *= 2.0;
    let mut copy = prd.ramp.stops[2];
    copy.at += 1.0;
    let mut blank = RampStop::default();
    if copy.at > 1.0 {
        blank.at = copy.at;
    }
    prd.ramp.stops[0] = blank;
}
