//! Structs, arrays, helpers and constants.

use super::*;

// ---------------------------------------------------------------------------
// Structs, arrays, helpers and constants
// ---------------------------------------------------------------------------

/// One stop of a colour ramp.
#[rt_struct]
pub struct Stop {
    pub at: f32,
    pub color: Vec3,
}

/// A struct holding an array of structs and an array of scalars.
#[rt_struct]
pub struct Ramp {
    pub stops: [Stop; 3],
    pub weights: [f32; 4],
    pub count: u32,
}

/// Running mean and count of samples.
#[rt_struct]
pub struct Accum {
    pub mean: Vec3,
    pub count: u32,
}

/// A helper with a function declared in its body.
#[rt_function]
pub fn smooth(x: f32) -> f32 {
    fn cube(v: f32) -> f32 {
        v * v * v
    }
    let t = x.clamp(0.0, 1.0);
    3.0 * t * t - 2.0 * cube(t)
}

/// A xorshift step: advances `state`, returns a float in [0, 1).
#[rt_function]
pub fn rand(state: &mut u32) -> f32 {
    let mut x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    (x >> 8) as f32 / 16777216.0
}

/// Adds one sample to `acc`.
#[rt_function]
pub fn accumulate(acc: &mut Accum, sample: Vec3) {
    acc.count += 1;
    acc.mean += (sample - acc.mean) / acc.count as f32;
}

/// Adds `n` random grey samples, passing its references on.
#[rt_function]
pub fn accumulate_noise(acc: &mut Accum, state: &mut u32, mut n: u32) {
    while n > 0 {
        let v = rand(state);
        accumulate(acc, Vec3::splat(v));
        n -= 1;
    }
}

/// A struct in (by reference), a struct out.
#[rt_function]
pub fn scaled(acc: &Accum, by: f32) -> Accum {
    Accum { mean: acc.mean * by, count: acc.count * 2 }
}

/// A ramp lookup: loops over an array of structs in a struct.
#[rt_function]
pub fn ramp_at(ramp: &Ramp, t: f32) -> Vec3 {
    let mut color = ramp.stops[0].color;
    for i in 1..3 {
        let lo = ramp.stops[i - 1];
        let hi = ramp.stops[i];
        if t >= lo.at && t < hi.at {
            color = lo.color + (hi.color - lo.color) * ((t - lo.at) / (hi.at - lo.at));
        }
    }
    color
}

/// Number of cells per side.
#[rt_const]
pub const STRATA: u32 = 4;
/// Cells, from another constant.
#[rt_const]
pub const CELLS: u32 = STRATA * STRATA;
/// A signed offset.
#[rt_const]
pub const BIAS: i32 = -2;
/// A vector constant.
#[rt_const]
pub const TINT: Vec3 = Vec3::new(0.9, 0.5, 0.25);
/// An array constant.
#[rt_const]
pub const STOPS: [f32; 3] = [0.5, 1.0, 2.0];

differential! {
    /// Arrays, structs, `#[rt_function]` helpers with `&`/`&mut`
    /// parameters, evaluation order, and constants.
    fn structs_arrays_helpers {
        /// Array literals, `[x; N]`, indexing and assignment with loop
        /// variables, arrays copied by value.
        arrays(a: i32) -> [i32; 6] over one(&i64_grid().into_iter().filter(|&a| a != i32::MIN).collect::<Vec<_>>()) => {
            let squares = [1, 4, 9, 16];
            let mut acc = [0i32; 4];
            for i in 0..4 {
                acc[i] = (a % 100) * squares[i];
            }
            let copy = acc;
            acc[0] = 7;
            let mut total = 0;
            for i in 0..4usize {
                total += copy[i];
            }
            let idx = (a & 3) as usize;
            [acc[0], copy[0], total, squares[idx], acc[3 - idx], [a, -a % 7, 3][(a & 1) as usize]]
        }
        /// Struct literals (fields in any order), nested structs, field
        /// assignment, copies, `T::default()`.
        structs(x: f32) -> [f32; 6] over one(&spread(64, -1.0, 2.0)) => {
            let first = Stop { at: x, color: Vec3::ONE };
            let mut ramp = Ramp {
                weights: [x, 2.0, 3.0, 4.0],
                count: 1,
                stops: [first, Stop { color: vec3(x, 0.0, 1.0), at: 0.5 }, Stop { at: 1.0, color: TINT }],
            };
            ramp.stops[1].color.y = x * 2.0;
            ramp.weights[3] *= x;
            let mut copy = ramp.stops[2];
            copy.at += 1.0;
            let blank = Stop::default();
            let other = Stop { color: Vec3::default(), at: blank.at };
            [
                ramp.stops[1].color.y, ramp.weights[3], copy.at, ramp.stops[2].at, blank.at + other.color.x,
                ramp.count as f32,
            ]
        }
        /// Arrays of structs and structs of arrays through helpers taking
        /// `&T`.
        ramp_lookup(t: f32) -> [Vec3; 1] over one(&spread(64, -0.5, 1.5)), tol ulp(3) => {
            let ramp = Ramp {
                stops: [
                    Stop { at: 0.0, color: vec3(1.0, 0.0, 0.0) },
                    Stop { at: 0.4, color: vec3(0.0, 1.0, 0.0) },
                    Stop { at: 1.0, color: vec3(0.0, 0.0, 1.0) },
                ],
                weights: [0.0; 4],
                count: 3,
            };
            [ramp_at(&ramp, t)]
        }
        /// An RNG whose state is a `&mut u32`, called repeatedly.
        rng(seed: u32) -> [f32; 4] over one(&u64_grid()), tol ulp(3) => {
            let mut s = seed | 1;
            let a = rand(&mut s);
            let b = rand(&mut s);
            [a, b, rand(&mut s) + rand(&mut s) * 2.0, (s >> 16) as f32]
        }
        /// Helpers updating a `&mut` struct and passing references on;
        /// `mut` value parameters; structs returned by value.
        accumulate_helpers(seed: u32) -> [Vec3; 3] over one(&u64_grid()), tol ulp(8) => {
            let mut s = seed | 1;
            let mut acc = Accum { mean: Vec3::ZERO, count: 0 };
            for _ in 0..3 {
                let c = vec3(rand(&mut s), rand(&mut s), rand(&mut s));
                accumulate(&mut acc, c);
            }
            accumulate_noise(&mut acc, &mut s, 4);
            let half = scaled(&acc, 0.5);
            [acc.mean, half.mean, vec3(acc.count as f32, half.count as f32, rand(&mut s))]
        }
        /// Calls with side effects run once each, in Rust's order: operands
        /// left to right, struct literal fields in source order, method
        /// receivers before arguments, `match` scrutinees once.
        evaluation_order(seed: u32) -> [f32; 6] over one(&u64_grid()), tol ulp(3) => {
            let mut s = seed | 1;
            let diff = rand(&mut s) - rand(&mut s);
            let swapped = Accum { count: (rand(&mut s) * 4.0) as u32, mean: Vec3::splat(rand(&mut s)) };
            let m = rand(&mut s).max(rand(&mut s) * 0.5);
            let lobe = match (rand(&mut s) * 3.0) as u32 {
                0 => 0.25,
                k => k as f32,
            };
            let arr = [rand(&mut s), rand(&mut s) * 10.0];
            [diff, swapped.count as f32, swapped.mean.x, m, lobe, arr[0] + arr[1]]
        }
        /// `#[rt_const]` items (scalar, computed, signed, vector, array) and
        /// `const` items in a body.
        constants(a: u32) -> [f32; 5] over one(&U16), tol CHAINED => {
            const GAMMA: f32 = 1.0 / 2.2;
            const STEPS: i32 = 3;
            let cell = ((a as i32 + BIAS + STEPS).abs() as u32) % CELLS;
            let stops = STOPS;
            let exposure = stops[(cell % STRATA) as usize % 3] + STOPS[cell as usize % 3];
            [cell as f32, exposure, TINT.y * GAMMA, (STRATA * 2) as f32, TINT.dot(Vec3::ONE)]
        }
        /// Functions declared in a body: a helper's, and the program's own
        /// (which calls a module-level helper and another nested one).
        nested_functions(a: u32) -> [f32; 2] over one(&U16), tol CHAINED => {
            fn halve(v: f32) -> f32 {
                v * 0.5
            }
            fn blend(v: f32) -> f32 {
                smooth(halve(v)) + halve(1.0)
            }
            let x = (a % 7) as f32 / 4.0;
            [smooth(x), blend(x)]
        }
        /// Struct update syntax: from another value (evaluated once, after
        /// the fields) and from `Default::default()` / `Accum::default()`.
        struct_update(a: u32) -> [f32; 6] over one(&U16) => {
            let mut s = a | 1;
            let base = Accum { mean: Vec3::splat(a as f32), count: 7 };
            let more = Accum { count: base.count + 1, ..base };
            let from_call = Accum { mean: Vec3::X, ..Accum { mean: Vec3::ONE, count: (rand(&mut s) * 8.0) as u32 } };
            let zeroed = Accum { count: a % 5, ..Default::default() };
            let stop = Stop { at: 0.5, ..Stop::default() };
            [more.mean.x + more.count as f32, from_call.mean.x, from_call.count as f32, zeroed.mean.y,
             zeroed.count as f32, stop.at + stop.color.z]
        }
    }
}
