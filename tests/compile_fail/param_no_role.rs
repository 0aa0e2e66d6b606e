// An any-hit parameter that is neither payload, attributes nor #[var].
use rt_std::prelude::*;

#[rt_payload]
pub struct Shadow {
    pub attenuation: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub normal: Vec3,
}

#[rt_program(any_hit)]
pub fn shadow(prd: &mut Shadow, attr: &Normals, ray_type: u32) {
    if ray_type == 1 {
        prd.attenuation = attr.normal;
    }
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &shadow::PROGRAM;

fn main() {}
