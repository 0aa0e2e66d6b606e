// An #[rt_attributes] struct used as the payload.
use rt_std::prelude::*;

#[rt_attributes]
pub struct Normals {
    pub normal: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Normals, #[var] bg_color: Vec3) {
    prd.normal = bg_color;
}

fn main() {}
