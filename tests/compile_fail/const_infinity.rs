// A module-level constant holding infinity: WGSL constants cannot (a
// conformant compiler rejects the shader), so the constant is the error.
use rt_std::prelude::*;

#[rt_const]
pub const FAR: f32 = f32::INFINITY;

fn main() {}
