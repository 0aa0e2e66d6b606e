// An enum whose variants carry fields: WGSL has no sum types.
use rt_std::prelude::*;

#[rt_enum]
pub enum Hit {
    Miss,
    Surface(f32),
}

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

fn main() {}
