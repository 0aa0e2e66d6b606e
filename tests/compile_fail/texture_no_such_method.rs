// A sampler method that does not exist (OpenGL's LOD bias): the error
// lists the methods there are.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shade {
    pub color: Vec3,
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade, #[var] env: Sampler2d) {
    let uv = current_ray().direction.xy();
    prd.color = env.sample_bias(uv, 1.0).xyz();
}

fn main() {}
