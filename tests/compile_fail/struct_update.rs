// Struct update syntax: every field must be written out.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub depth: i32,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    *prd = Radiance { result: bg_color, ..*prd };
}

fn main() {}
