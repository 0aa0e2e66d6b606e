// A range pattern: WGSL's switch cases are plain values.
use rt_std::prelude::*;

#[rt_function]
pub fn classify(x: u32) -> u32 {
    match x {
        0..=9 => 0,
        _ => 1,
    }
}

fn main() {}
