// A trait object parameter: traits dispatch statically in ray programs;
// the code chosen at run time is a callable program called through an id.
use rt_std::prelude::*;

#[rt_trait]
pub trait Shade {
    fn shade(&self) -> f32;
}

#[rt_function]
pub fn brightness(s: &dyn Shade) -> f32 {
    s.shade()
}

fn main() {}
