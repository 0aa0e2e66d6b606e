// An `Option` as a buffer element: store a flag and a value.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn write_hits(#[var] mut hits: RwBuffer<Option<f32>>) {
    hits[launch_index().x] = None;
}

fn main() {}
