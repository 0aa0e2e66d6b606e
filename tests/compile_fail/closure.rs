// A closure that escapes (here stored under another name): closures are
// inlined where they are called, and this one is not only called.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    let scale = |c: Vec3| c * 0.5;
    let also = scale;
    prd.result = also(bg_color);
}

// Code that uses the program still compiles: only the mistake is reported.
pub static REGISTERED: &rt_std::program::ProgramDescriptor = &miss::PROGRAM;

fn main() {}
