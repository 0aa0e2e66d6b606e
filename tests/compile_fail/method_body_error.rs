// A type error inside a method is reported once, at the method, not again
// at each program that calls it.
use rt_std::prelude::*;

#[rt_payload(impl)]
pub struct Shade {
    pub color: Vec3,
}

#[rt_impl]
impl Shade {
    pub fn dim(&mut self, k: f32) {
        self.color = self.color * k + 1;
    }
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.dim(0.5);
}

#[rt_program(closest_hit)]
pub fn hit(prd: &mut Shade) {
    prd.dim(0.25);
}

fn main() {}
