// A method bindless ids do not have.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn read(#[var] data: BindlessBuffer<u32>, #[var] mut out: RwBuffer<u32>) {
    out[0] = data.size();
}

fn main() {}
