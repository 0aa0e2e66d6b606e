// A `debug_assert!` message with arguments: the GPU has no strings.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn asserting(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    debug_assert!(i < 4, "index {} past the end", i);
    out[i] = i;
}

fn main() {}
