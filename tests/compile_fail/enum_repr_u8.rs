// An `#[rt_enum]` with a `repr` other than `u32`: an enum is a `u32` in WGSL.
use rt_std::prelude::*;

#[rt_enum]
#[repr(u8)]
pub enum Lobe {
    Diffuse,
    Specular,
}

fn main() {}
