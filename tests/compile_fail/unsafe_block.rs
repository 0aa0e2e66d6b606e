// An unsafe block: ray programs are safe code.
use rt_std::prelude::*;

#[rt_function]
pub fn bits(x: f32) -> u32 {
    unsafe { core::mem::transmute::<f32, u32>(x) }
}

fn main() {}
