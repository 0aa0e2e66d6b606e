// The bitwise updates are for integers only.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn scramble(#[var] values: RwBuffer<f32>) {
    values.atomic_xor(0, 1.0);
}

fn main() {}
