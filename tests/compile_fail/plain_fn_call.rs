// Calling a plain Rust function that is not an #[rt_function].
use rt_std::prelude::*;

pub fn tone_map(c: Vec3) -> Vec3 {
    c / (c + Vec3::ONE)
}

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = tone_map(bg_color);
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &miss::PROGRAM;

fn main() {}
