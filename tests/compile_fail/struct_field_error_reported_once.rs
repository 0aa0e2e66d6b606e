// A mistake in a struct is reported once, at the struct: not again where a
// program uses it, and not as "cannot find type".
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
    pub depth: u8,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &miss::PROGRAM;

fn main() {}
