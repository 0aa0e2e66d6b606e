// `BindlessBuffer::NONE` where nothing says the element type.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn read(#[var] mut out: RwBuffer<u32>) {
    out[0] = BindlessBuffer::NONE.len();
}

fn main() {}
