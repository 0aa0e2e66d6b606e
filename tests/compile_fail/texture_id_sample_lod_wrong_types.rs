// Sampling through a texture id with the LOD where the coordinates go.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn generate(#[var] tex: BindlessSampler<Sampler2d>, #[var] mut out: RwBuffer<Vec4>) {
    out[0] = tex.sample_lod(0.5, vec2(0.5, 0.5));
}

fn main() {}
