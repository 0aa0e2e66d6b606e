// A tuple holding a heap type: programs have no heap.
use rt_std::prelude::*;

#[rt_function]
pub fn first(pair: (f32, Vec<f32>)) -> f32 {
    pair.0
}

fn main() {}
