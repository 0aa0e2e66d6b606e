// `#[rt_program]` without a kind.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program]
pub fn shade(prd: &mut Radiance) {
    prd.result = Vec3::ONE;
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &shade::PROGRAM;

fn main() {}
