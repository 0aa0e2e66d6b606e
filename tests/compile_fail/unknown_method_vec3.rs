// A glam method the compiler has no WGSL for.
use rt_std::prelude::*;

#[rt_function]
pub fn angle(a: Vec3, b: Vec3) -> f32 {
    a.angle_between(b)
}

fn main() {}
