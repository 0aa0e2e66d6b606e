// A tuple expression: WGSL has no tuples.
use rt_std::prelude::*;

#[rt_function]
pub fn pair(x: f32) -> f32 {
    let p = (x, x * 2.0);
    p.0 + p.1
}

fn main() {}
