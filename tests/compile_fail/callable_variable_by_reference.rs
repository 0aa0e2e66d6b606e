// A callable program's `#[var]` is taken by value, as a program's is.
use rt_std::prelude::*;

#[rt_program(callable)]
pub fn tint(c: Vec3, #[var] strength: &f32) -> Vec3 {
    c * *strength
}

fn main() {}
