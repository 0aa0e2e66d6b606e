// An 8-bit integer: WGSL has 32-bit integers only.
use rt_std::prelude::*;

#[rt_function]
pub fn channel(x: f32) -> u32 {
    let c: u8 = 255;
    (x * c as f32) as u32
}

fn main() {}
