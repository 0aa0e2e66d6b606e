// A miss program has no instance, so no transform to read.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance) {
    let m = rt_get_transform(ObjectToWorld);
    prd.result = m.w_axis.truncate();
}

fn main() {}
