// A ray-generation program traces rays; it is not running for one.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn camera(#[var] mut out: RwBuffer<u32>) {
    out[launch_index().x] = ray_flags() + ray_mask();
}

fn main() {}
