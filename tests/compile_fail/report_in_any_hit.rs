// rt_report_intersection belongs to intersection programs.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shadow {
    pub attenuation: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub normal: Vec3,
}

#[rt_program(any_hit)]
pub fn shadow(prd: &mut Shadow, attr: &Normals) {
    prd.attenuation = attr.normal;
    rt_report_intersection(0);
}

fn main() {}
