// A match guard: WGSL's switch cases are plain values.
use rt_std::prelude::*;

#[rt_function]
pub fn classify(x: i32) -> u32 {
    match x {
        n if n > 10 => 2,
        0 => 0,
        _ => 1,
    }
}

fn main() {}
