// A reference bound to a local: WGSL locals hold values, not references.
use rt_std::prelude::*;

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    let color = bg_color;
    let r = &color;
    prd.result = *r;
}

fn main() {}
