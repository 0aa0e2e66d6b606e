// A cube map read with `sample`, the 2D samplers' method: cube maps are
// read by direction with `sample_dir`.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade, #[var] cube: SamplerCube) {
    let d = current_ray().direction;
    prd.color = cube.sample(d.xy()).xyz();
}

fn main() {}
