// A variant the enum does not have.
use rt_std::prelude::*;

#[rt_enum]
pub enum Lobe {
    Diffuse,
    Specular,
}

#[rt_function]
pub fn weight(l: Lobe) -> f32 {
    if l == Lobe::Glossy { 0.5 } else { 1.0 }
}

fn main() {}
