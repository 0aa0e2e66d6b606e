// A glam method the compiler has no WGSL for.
use rt_std::prelude::*;

#[rt_function]
pub fn halfway(a: Vec3, b: Vec3) -> Vec3 {
    a.slerp(b, 0.5)
}

fn main() {}
