// A tuple return type: WGSL has no tuples.
use rt_std::prelude::*;

#[rt_function]
pub fn min_max(a: f32, b: f32) -> (f32, f32) {
    (a.min(b), a.max(b))
}

fn main() {}
