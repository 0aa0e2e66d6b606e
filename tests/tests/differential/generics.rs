//! Generic `#[rt_function]`s, one WGSL function per instance: bounded by
//! std's operator traits and unbounded, at scalars, glam vectors, a user
//! struct and arrays of a const length; the arguments inferred from the
//! call's argument types (an integer literal taking the other argument's
//! type) or given by a turbofish; a generic calling a generic, a helper
//! calling a generic, `&mut T` parameters.

use super::*;
use core::ops::{Add, Mul, Sub};

/// Linear interpolation over anything with `+`, `-` and `* f32`.
#[rt_function]
pub fn lerp_any<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f32, Output = T>>(a: T, b: T, t: f32) -> T {
    a + (b - a) * t
}

/// A generic calling a generic at its own parameter.
#[rt_function]
pub fn midpoint<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<f32, Output = T>>(a: T, b: T) -> T {
    lerp_any(a, b, 0.5)
}

/// The larger of two, for any ordered type.
#[rt_function]
pub fn larger<T: Copy + PartialOrd>(a: T, b: T) -> T {
    if a > b { a } else { b }
}

/// Unbounded: the body needs nothing of `T`.
#[rt_function]
pub fn pick<T>(first: bool, a: T, b: T) -> T {
    if first { a } else { b }
}

/// Exchanges two places of any type.
#[rt_function]
pub fn exchange<T: Copy>(a: &mut T, b: &mut T) {
    let t = *a;
    *a = *b;
    *b = t;
}

/// The sum of an array of any length.
#[rt_function]
pub fn total<const N: usize>(a: [f32; N]) -> f32 {
    let mut s = 0.0;
    for i in 0..N {
        s += a[i];
    }
    s
}

/// The last element of an array of any type and length.
#[rt_function]
pub fn last_of<T: Copy, const N: usize>(a: [T; N]) -> T {
    a[N - 1]
}

/// A plain helper calling a generic.
#[rt_function]
pub fn tint(c: Vec3, k: f32) -> Vec3 {
    lerp_any(c, Vec3::ONE, k)
}

/// A user struct as a type argument.
#[rt_struct]
pub struct Span2 {
    pub lo: f32,
    pub hi: f32,
}

differential! {
    /// Generic helpers at several types each.
    fn generic_helpers {
        /// One generic at `f32` and `Vec3`, inferred and by turbofish; a
        /// generic through a generic; a helper through a generic.
        lerp_at_two_types(a: f32, b: f32) -> [f32; 6] over pairs(&spread(9, -4.0, 4.0), &spread(7, -2.0, 3.0)), tol CHAINED => {
            let s = lerp_any(a, b, 0.25);
            let v = lerp_any::<Vec3>(Vec3::new(a, b, 1.0), Vec3::new(b, a, -1.0), 0.75);
            let m = midpoint(Vec3::splat(a), Vec3::splat(b));
            let t = tint(Vec3::new(a, b, 0.5), 0.5);
            [s, v.x + v.y * 2.0, v.z, m.y, t.x + t.y, midpoint(a, b)]
        }
        /// `larger` at `i32`, `u32` (an integer literal taking the other
        /// argument's type), `f32` and a struct-free `pick` at a struct.
        ordered(x: i32, y: u32) -> [u32; 4] over pairs(&[-7, -1, 0, 3, 100], &[0u32, 1, 5, 4000000000]) => {
            let a = larger(x, -3);
            let b = larger(3, y);
            let c = larger(x as f32 * 0.5, 1.25);
            let span = pick(x > 0, Span2 { lo: 0.0, hi: 1.0 }, Span2 { lo: -1.0, hi: 2.0 });
            [a as u32, b, (c * 4.0) as i32 as u32, (span.hi - span.lo) as u32 + pick::<u32>(y > 3, 10, 20)]
        }
        /// `&mut T` at `f32` and `UVec3`; arrays of lengths 2, 3 and 4.
        places_and_lengths(a: f32, b: f32) -> [f32; 6] over pairs(&spread(5, -2.0, 2.0), &spread(4, 0.5, 3.0)), tol CHAINED => {
            let mut p = a;
            let mut q = b;
            exchange(&mut p, &mut q);
            let mut u = UVec3::new(1, 2, 3);
            let mut w = UVec3::new(7, 8, 9);
            exchange(&mut u, &mut w);
            let three = [a, b, a * b];
            [p - q, (u.x + w.z) as f32, total(three), total::<2>([a, b]), total([1.0, a, b, 2.0]), last_of(three) + last_of([u.y, w.y]) as f32]
        }
    }
}

/// A payload for the program pair below.
#[rt_payload]
pub struct Shade {
    pub v: f32,
}

#[rt_program(miss)]
pub fn generic_miss(prd: &mut Shade) {
    prd.v = lerp_any(prd.v, 10.0, 0.5);
}

#[rt_program(ray_generation)]
pub fn generic_trace(#[var] top: Object, #[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    let mut prd = Shade { v: lerp_any(0.0, i as f32, 0.5) };
    rt_trace(top, Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 1.0), &mut prd);
    out[i] = prd.v;
}

/// Two programs of one launch use one instance: the megakernel has it
/// once, and every backend gives the same values.
#[test]
fn an_instance_two_programs_use_is_linked_once() {
    for on in [On::CPU, On::COMPUTE, On::RAY_QUERY].into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_max_trace_depth(1);
        let miss = ctx.create_program(&generic_miss::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        let top = ctx.create_geometry_group(&[], Acceleration::default()).unwrap();
        let p = ctx.create_program(&generic_trace::PROGRAM);
        ctx.set_var(p, "top", top).unwrap();
        let out = ctx.create_buffer(BufferType::Output, vec![0.0f32; 8]);
        ctx.set_var(p, "out", out).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        ctx.launch(0, 8, 1).unwrap();
        let got: Vec<f32> = ctx.read_buffer(out).unwrap();
        let want: Vec<f32> = (0..8).map(|i| i as f32 * 0.25 + 5.0).collect();
        assert_eq!(got, want, "{on:?}");
        if on != On::CPU {
            let wgsl = ctx.linked_wgsl().expect("a wgpu launch keeps its kernel");
            assert_eq!(wgsl.matches("fn rtf_lerp_any__f32(").count(), 1, "{on:?}");
        }
    }
}
