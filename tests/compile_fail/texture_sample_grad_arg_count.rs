// `sample_grad` with one footprint side where it takes two.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade, #[var] env: Sampler2d) {
    let uv = current_ray().direction.xy();
    prd.color = env.sample_grad(uv, vec2(0.01, 0.0)).xyz();
}

fn main() {}
