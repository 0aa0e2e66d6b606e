// rt_terminate_ray belongs to any-hit programs.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub normal: Vec3,
}

#[rt_program(closest_hit)]
pub fn shade(prd: &mut Radiance, attr: &Normals) {
    prd.result = attr.normal;
    rt_terminate_ray();
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &shade::PROGRAM;

fn main() {}
