// The `?` operator: programs have no Option/Result to propagate.
use rt_std::prelude::*;

#[rt_function]
pub fn half(x: f32) -> f32 {
    let y = x?;
    y * 0.5
}

fn main() {}
