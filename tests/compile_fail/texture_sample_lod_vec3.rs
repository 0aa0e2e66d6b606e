// `sample_lod` of a 2D sampler given a 3D coordinate.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade, #[var] env: Sampler2d) {
    let d = current_ray().direction;
    prd.color = env.sample_lod(d, 2.0).xyz();
}

fn main() {}
