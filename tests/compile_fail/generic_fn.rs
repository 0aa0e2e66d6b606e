// A generic helper: WGSL functions are monomorphic.
use rt_std::prelude::*;

#[rt_function]
pub fn twice<T: Copy + core::ops::Add<Output = T>>(x: T) -> T {
    x + x
}

fn main() {}
