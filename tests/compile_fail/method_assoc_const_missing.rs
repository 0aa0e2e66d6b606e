// An associated constant the impl does not declare.
use rt_std::prelude::*;

#[rt_struct(impl)]
pub struct Sphere {
    pub radius: f32,
}

#[rt_impl]
impl Sphere {
    pub const UNIT: f32 = 1.0;
}

#[rt_program(ray_generation)]
pub fn unit(#[var] mut out: RwBuffer<f32>) {
    out[launch_index().x] = Sphere::UNITS;
}

fn main() {}
