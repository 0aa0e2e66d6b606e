// A method calling a helper that names the method's own type: the chain
// cannot close (the struct's link waits for the impl's, which waits for
// the helper's, which waits for the struct's).
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Sphere {
    pub radius: f32,
}

#[rt_function]
pub fn area_of(s: &Sphere) -> f32 {
    12.566371 * s.radius * s.radius
}

#[rt_impl]
impl Sphere {
    pub fn area(&self) -> f32 {
        area_of(self)
    }
}

fn main() {}
