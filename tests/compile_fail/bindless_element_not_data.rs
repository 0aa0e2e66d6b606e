// A bindless id of a type that cannot be a buffer element.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn read(#[var] samplers: BindlessBuffer<Sampler2d>, #[var] mut out: RwBuffer<u32>) {
    out[0] = samplers.len();
}

fn main() {}
