// A mistake in a helper is reported once, at the helper, not again at
// every program that calls it.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_function]
pub fn gamma(c: Vec3) -> Vec3 {
    let r = &c;
    vec3(r.x.powf(1.0 / 2.2), r.y.powf(1.0 / 2.2), r.z.powf(1.0 / 2.2))
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = gamma(bg_color);
}

#[rt_program(closest_hit)]
pub fn shade(prd: &mut Radiance) {
    prd.result = gamma(Vec3::ONE);
}

pub static PROGRAMS: [&rt_std::program::ProgramDescriptor; 2] = [&miss::PROGRAM, &shade::PROGRAM];

fn main() {}
