// A Vec local: programs have no heap.
use rt_std::prelude::*;

#[rt_function]
pub fn sum() -> f32 {
    let weights: Vec<f32> = Vec::new();
    let _ = weights;
    0.0
}

fn main() {}
