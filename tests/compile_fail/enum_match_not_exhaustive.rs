// A `match` on an `#[rt_enum]` that leaves a variant out: rustc's own
// exhaustiveness check (no `_` is needed when every variant is listed).
use rt_std::prelude::*;

#[rt_enum]
pub enum Lobe {
    Diffuse,
    Specular,
    Transmission,
}

#[rt_payload]
pub struct Radiance {
    pub result: Vec3,
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] lobe: Lobe) {
    prd.result = match lobe {
        Lobe::Diffuse => Vec3::ONE,
        Lobe::Specular => Vec3::ZERO,
    };
}

fn main() {}
