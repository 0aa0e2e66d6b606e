// `match` on an f32: WGSL's switch takes integers only.
use rt_std::prelude::*;

#[rt_function]
pub fn classify(x: f32) -> u32 {
    match x {
        0.0 => 0,
        _ => 1,
    }
}

fn main() {}
