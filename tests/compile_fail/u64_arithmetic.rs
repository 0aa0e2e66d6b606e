// 64-bit integer arithmetic in a program: one error at the type, nothing
// after it about the traits the CPU copy's integer semantics use.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn hash(#[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    let h: u64 = i as u64 * 2654435761 + 7;
    out[i] = (h >> 16) as u32 % 1024;
}

fn main() {}
