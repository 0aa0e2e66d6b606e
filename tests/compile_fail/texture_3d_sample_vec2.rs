// A 3D sampler sampled with a 2D coordinate.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn fog(prd: &mut Shade, #[var] volume: Sampler3d) {
    let uv = current_ray().direction.xy();
    prd.color = volume.sample(uv).xyz();
}

fn main() {}
