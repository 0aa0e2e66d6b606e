// A glam method the compiler has no WGSL for: `map` takes a closure.
use rt_std::prelude::*;

#[rt_function]
pub fn rounded(a: Vec3) -> Vec3 {
    a.map(|x| x.round())
}

fn main() {}
