// An enum declared with `#[rt_struct]`: enums have their own attribute.
use rt_std::prelude::*;

#[rt_struct]
pub enum Lobe {
    Diffuse,
    Specular,
}

fn main() {}
