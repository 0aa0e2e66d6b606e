// A callable called with an argument of the wrong type.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn shade(#[var] brdf: Callable<fn(Vec3, Vec3) -> Vec3>, #[var] mut out: RwBuffer<Vec3>) {
    out[0] = brdf.call(Vec3::Z, 1.0);
}

fn main() {}
