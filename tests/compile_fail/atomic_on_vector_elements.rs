// An atomic update is of one 32-bit word: a buffer of vectors has none.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn accumulate(#[var] colors: RwBuffer<Vec3>) {
    colors.atomic_add(launch_index().x, Vec3::ONE);
}

fn main() {}
