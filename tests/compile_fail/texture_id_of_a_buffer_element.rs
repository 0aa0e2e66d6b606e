// A bindless sampler id names a sampler type, not an element type.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn generate(#[var] tex: BindlessSampler<Vec4>, #[var] mut out: RwBuffer<u32>) {
    out[0] = tex.id();
}

fn main() {}
