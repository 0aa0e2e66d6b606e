// A plain `const` used in a program: constants programs use are declared
// with #[rt_const].
use rt_std::prelude::*;

pub const SCALE: f32 = 0.5;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color * SCALE;
}

fn main() {}
