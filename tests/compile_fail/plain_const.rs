// A plain `const` of another module used in a program: the macros see
// plain constants only in the program's own module; others are declared
// with #[rt_const].
use rt_std::prelude::*;

mod settings {
    pub const SCALE: f32 = 0.5;
}
use settings::SCALE;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color * SCALE;
}

fn main() {}
