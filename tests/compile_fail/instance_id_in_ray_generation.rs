// A ray-generation program traces rays; no instance is hit in it.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] mut out: RwBuffer<u32>) {
    out[launch_index().x] = instance_id();
}

fn main() {}
