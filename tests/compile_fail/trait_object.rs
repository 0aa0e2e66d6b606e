// A trait object parameter: WGSL has no dynamic dispatch.
use rt_std::prelude::*;

pub trait Shade {
    fn shade(&self) -> f32;
}

#[rt_function]
pub fn brightness(s: &dyn Shade) -> f32 {
    s.shade()
}

fn main() {}
