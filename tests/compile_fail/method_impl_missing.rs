// A struct declared `(impl)` without an #[rt_impl] block.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Sphere {
    pub radius: f32,
}

fn main() {}
