// An f64 local: the GPU computes in f32.
use rt_std::prelude::*;

#[rt_function]
pub fn gamma() -> f32 {
    let g: f64 = 2.2;
    g as f32
}

fn main() {}
