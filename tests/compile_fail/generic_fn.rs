// A generic helper that calls itself: each instance is a WGSL function,
// and WGSL has no recursion, at any type.
use rt_std::prelude::*;

#[rt_function]
pub fn halve<T: Copy + core::ops::Mul<f32, Output = T>>(x: T, n: u32) -> T {
    if n == 0 { x } else { halve(x * 0.5, n - 1) }
}

#[rt_program(ray_generation)]
pub fn render(#[var] mut out: RwBuffer<f32>) {
    let i = launch_index().x;
    out[i] = halve(i as f32, 3);
}

fn main() {}
