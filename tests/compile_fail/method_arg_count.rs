// A method called with the wrong number of arguments.
use rt_std::prelude::*;

#[rt_function]
pub fn cosine(a: Vec3, b: Vec3) -> f32 {
    a.dot(b, b)
}

fn main() {}
