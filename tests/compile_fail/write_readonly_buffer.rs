// Indexing assignment into a read-only Buffer.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] output: Buffer<Vec4>) {
    let idx = launch_index();
    output[idx.x] = Vec4::ONE;
}

fn main() {}
