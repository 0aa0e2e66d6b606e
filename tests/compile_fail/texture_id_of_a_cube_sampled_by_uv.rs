// A cube map's id sampled with a 2D sampler's method.
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn sky(#[var] env: BindlessSampler<SamplerCube>, #[var] mut out: RwBuffer<Vec4>) {
    out[0] = env.sample_lod(vec2(0.5, 0.5), 1.0);
}

fn main() {}
