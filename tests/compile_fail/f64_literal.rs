// An f64 literal: the GPU computes in f32.
use rt_std::prelude::*;

#[rt_function]
pub fn gamma() -> f32 {
    let g = 2.2f64;
    g as f32
}

fn main() {}
