// Which side of a triangle was hit means nothing to a miss program.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance) {
    if is_triangle_hit_front_face() {
        prd.result = Vec3::ONE;
    }
}

fn main() {}
