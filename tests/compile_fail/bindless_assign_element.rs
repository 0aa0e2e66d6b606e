// Assigning to an element through a bindless id: ids write with `.store`.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn fill(#[var] data: RwBindlessBuffer<u32>) {
    data[launch_index().x] = 1;
}

fn main() {}
