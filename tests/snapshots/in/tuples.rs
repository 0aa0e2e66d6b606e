//! Tuples: helpers taking and returning `(f32, f32)`, tuple literals,
//! `.0`/`.1` (read and assigned), `let` patterns (nested, `_`, `mut`),
//! glam's tuple-returning `sin_cos`, a struct field of a tuple type, and
//! `match` on a tuple of integers (literals, `|`, bindings, `_`).
use rt_std::prelude::*;

/// A polar sample as a struct field.
#[rt_struct]
pub struct PolarSample {
    pub angles: (f32, f32),
    pub index: u32,
}

/// A concentric disk mapping's two coordinates at once.
#[rt_function]
pub fn disk(u: f32, v: f32) -> (f32, f32) {
    let (s, c) = (u * PI).sin_cos();
    (s * v, c * v)
}

/// The quadrant of a cell: a `match` on a tuple of integers.
#[rt_function]
pub fn quadrant(cell: (i32, i32)) -> u32 {
    match cell {
        (0, 0) => 0,
        (0, _) | (_, 0) => 1,
        (x, 1) => x as u32 + 10,
        _ => 99,
    }
}

#[rt_program(ray_generation)]
pub fn tuples(#[var] samples: Buffer<PolarSample>, #[var] mut out: RwBuffer<Vec3>) {
    let i = launch_index().x;
    let sample = samples[i];
    let (mut x, y) = disk(sample.angles.0, sample.angles.1);
    x += 1.0;
    let mut pair = (x, (y, sample.index));
    pair.0 *= 2.0;
    let (a, (_, n)) = pair;
    let q = quadrant((n as i32 % 3, i as i32 % 2));
    out[i] = Vec3::new(a, (pair.1).0, (q + n) as f32);
}

/// Integers in tuple literals inferred from later uses, as in Rust: `t.0`
/// read as a `u32`, a destructured element added to a `u32`, a nested
/// tuple's element, and one nothing decides (`i32`).
#[rt_program(ray_generation)]
pub fn tuples_inferred(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let t = (5, 2.0);
    let x: u32 = t.0 + i;
    let (a, b) = (7, 1);
    let y = a + i;
    let n = ((1, 4294967295), 3);
    let z: u32 = (n.0).1;
    let mut m = (3, 0.5);
    m.0 += i;
    out[i] = x + y + z + m.0 + (b + n.1 + (n.0).0) as u32 + t.1 as u32;
}
