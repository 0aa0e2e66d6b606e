// `impl Trait` in a helper's parameter: name a type parameter instead.
use rt_std::prelude::*;

#[rt_function]
pub fn double(x: impl Copy + core::ops::Add<Output = f32>) -> f32 {
    x + x
}

fn main() {}
