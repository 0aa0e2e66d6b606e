// Mat4::inverse: WGSL has no matrix inverse.
use rt_std::prelude::*;

#[rt_function]
pub fn to_object(m: Mat4, p: Vec4) -> Vec4 {
    m.inverse() * p
}

fn main() {}
