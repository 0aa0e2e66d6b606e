// Writing through a read-only bindless id.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn fill(#[var] data: BindlessBuffer<u32>) {
    data.store(launch_index().x, 1);
}

fn main() {}
