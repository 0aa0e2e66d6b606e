// A Box parameter: programs have no heap.
use rt_std::prelude::*;

#[rt_function]
pub fn unbox(v: Box<f32>) -> f32 {
    *v
}

fn main() {}
