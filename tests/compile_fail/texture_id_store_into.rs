// Writing texels through a bindless sampler id: samplers are read-only.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn generate(#[var] mut tex: BindlessSampler<Sampler2d>) {
    tex[0] = vec4(1.0, 0.0, 0.0, 1.0);
}

fn main() {}
