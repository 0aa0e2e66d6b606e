// A callable program reads no `#[var]` variables.
use rt_std::prelude::*;

#[rt_program(callable)]
pub fn tint(c: Vec3, #[var] strength: f32) -> Vec3 {
    c * strength
}

fn main() {}
