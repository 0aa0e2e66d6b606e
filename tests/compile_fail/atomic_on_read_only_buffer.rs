// Atomics write: a read-only `Buffer` cannot take them.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn count(#[var] hits: Buffer<u32>) {
    hits.atomic_add(launch_index().x, 1);
}

fn main() {}
