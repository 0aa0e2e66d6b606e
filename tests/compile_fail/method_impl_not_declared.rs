// An #[rt_impl] block for a struct declared without `(impl)`: the struct's
// link in the chain does not carry the impl.
use rt_std::prelude::*;

#[rt_struct]
pub struct Sphere {
    pub radius: f32,
}

#[rt_impl]
impl Sphere {
    pub fn area(&self) -> f32 {
        12.566371 * self.radius * self.radius
    }
}

fn main() {}
