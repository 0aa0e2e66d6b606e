// A struct used by a program but not declared with #[rt_struct]: rustc
// reports it as a missing macro at the use.
use rt_std::prelude::*;

#[derive(Clone, Copy)]
pub struct Light {
    pub color: Vec3,
}

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    let light = Light { color: bg_color };
    prd.result = light.color;
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &miss::PROGRAM;

fn main() {}
