// f32 + i32: no implicit conversions (rustc reports it on the CPU copy too).
use rt_std::prelude::*;

#[rt_function]
pub fn scaled(x: f32, n: i32) -> f32 {
    x + n
}

fn main() {}
