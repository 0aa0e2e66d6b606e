// An `Option` of a heap type: programs have no heap.
use rt_std::prelude::*;

#[rt_function]
pub fn weights(n: u32) -> f32 {
    let w: Option<Vec<f32>> = None;
    let _ = w;
    n as f32
}

fn main() {}
