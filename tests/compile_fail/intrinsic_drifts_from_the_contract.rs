// rt-std's CPU body of an intrinsic must have its contract row's signature:
// here the transform kind is taken as a bare u32 and the result is a Vec4.
use glam::Vec4;

#[rt_macros::rt_intrinsic]
pub fn rt_get_transform(kind: u32) -> Vec4 {
    Vec4::splat(kind as f32)
}

fn main() {}
