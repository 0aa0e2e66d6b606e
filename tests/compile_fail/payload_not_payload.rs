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

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &miss::PROGRAM;

fn main() {}
