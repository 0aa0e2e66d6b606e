//! Generic helpers (`#[rt_function] fn f<T>`): one WGSL function per
//! instance, named after its arguments (`rtf_blend__f32`,
//! `rtf_blend__Vec3`); arguments inferred from the call's argument types or
//! given by a turbofish; a const parameter as an array length; a generic
//! calling a generic; a generic's instance shared by a helper and the
//! program.
use rt_std::prelude::*;

/// Interpolation over anything with `+`, `-` and `* f32`.
#[rt_function]
pub fn blend<T>(a: T, b: T, t: f32) -> T
where
    T: Copy + core::ops::Add<Output = T> + core::ops::Sub<Output = T> + core::ops::Mul<f32, Output = T>,
{
    a + (b - a) * t
}

/// The average of an array of any length.
#[rt_function]
pub fn average<const N: usize>(xs: [f32; N]) -> f32 {
    let mut s = 0.0;
    let mut i = 0;
    while i < N {
        s += xs[i];
        i += 1;
    }
    s / N as f32
}

/// A generic through a generic.
#[rt_function]
pub fn halfway<T: Copy + core::ops::Add<Output = T> + core::ops::Sub<Output = T> + core::ops::Mul<f32, Output = T>>(
    a: T,
    b: T,
) -> T {
    blend(a, b, 0.5)
}

/// A plain helper using an instance the program uses too.
#[rt_function]
pub fn fade(c: Vec3) -> Vec3 {
    blend(c, Vec3::ZERO, 0.25)
}

#[rt_program(ray_generation)]
pub fn generic_blend(#[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let x = i as f32;
    let a = blend(x, 1.0, 0.5);
    let c = blend::<Vec3>(Vec3::X, Vec3::Y, x);
    let d = halfway(c, fade(c));
    let m = average([x, 2.0, a]) + average::<2>([x, x]);
    out[i] = Vec4::new(a, d.x, d.y, m);
}
