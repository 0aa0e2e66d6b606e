// A type alias in a program without `#[rt_type]`: the macros that compile
// programs see only items declared with an rt attribute.
use rt_std::prelude::*;

pub type Brdf = Vec3;

#[rt_function]
pub fn dim(c: Brdf) -> Brdf {
    c * 0.5
}

fn main() {}
