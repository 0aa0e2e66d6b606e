//! Helpers that take references: an RNG whose state is a `&mut u32`,
//! helpers that take and return structs, a helper that updates a `&mut`
//! struct field by field and passes its reference on to another helper,
//! `&T` parameters, and `mut` value parameters; RNG calls inside a method
//! receiver, an out-of-order struct literal and a `match` scrutinee each
//! run once, in Rust's order.
use rt_std::prelude::*;

/// A xorshift step: advances `state` and returns a float in [0, 1).
#[rt_function]
pub fn rand(state: &mut u32) -> f32 {
    let mut x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    (x >> 8) as f32 / 16777216.0
}

/// Running mean and count of samples.
#[rt_struct]
pub struct Accum {
    pub mean: Vec3,
    pub count: u32,
}

/// Adds one sample to `acc`.
#[rt_function]
pub fn accumulate(acc: &mut Accum, sample: Vec3) {
    acc.count += 1;
    acc.mean += (sample - acc.mean) / acc.count as f32;
}

/// Adds `n` random grey samples, through the references it was given.
#[rt_function]
pub fn accumulate_noise(acc: &mut Accum, state: &mut u32, mut n: u32) {
    while n > 0 {
        let v = rand(state);
        accumulate(acc, Vec3::splat(v));
        n -= 1;
    }
}

/// A struct in, a struct out.
#[rt_function]
pub fn scaled(acc: &Accum, by: f32) -> Accum {
    Accum { mean: acc.mean * by, count: acc.count }
}

#[rt_program(ray_generation)]
pub fn helpers_refs(#[var] frame: u32, #[var] samples: u32, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let mut seed = (idx.x * 1973 + idx.y * 9277 + frame * 26699) | 1;
    let mut acc = Accum { mean: Vec3::ZERO, count: 0 };
    for _ in 0..samples {
        let c = vec3(rand(&mut seed), rand(&mut seed), rand(&mut seed));
        accumulate(&mut acc, c);
    }
    accumulate_noise(&mut acc, &mut seed, 4);
    let half = scaled(&acc, 0.5);
    // Calls with side effects are evaluated once each, in source order.
    let jitter = (rand(&mut seed) * 8.0).fract();
    let swapped = Accum { count: (rand(&mut seed) * 4.0) as u32, mean: Vec3::splat(rand(&mut seed)) };
    let lobe = match (rand(&mut seed) * 3.0) as u32 {
        0 => 0.25,
        k => k as f32,
    };
    out[idx] = (half.mean + jitter * 0.01 + swapped.mean * lobe).extend((half.count + swapped.count) as f32);
}
