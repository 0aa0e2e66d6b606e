// A 3D sampler's footprint given as 2D derivatives.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn fog(prd: &mut Shade, #[var] volume: Sampler3d) {
    let uvw = current_ray().direction;
    prd.color = volume.sample_grad(uvw, vec2(0.01, 0.0), vec2(0.0, 0.01)).xyz();
}

fn main() {}
