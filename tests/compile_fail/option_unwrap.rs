// `unwrap` on an `Option`: a `None` would panic on the CPU.
use rt_std::prelude::*;

#[rt_function]
pub fn first(o: Option<f32>) -> f32 {
    o.unwrap()
}

fn main() {}
