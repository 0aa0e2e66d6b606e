// A helper that calls rt_trace cannot be called from an any-hit program.
use rt_std::prelude::*;

#[rt_payload]
pub struct Shadow {
    pub attenuation: Vec3,
}

#[rt_attributes]
pub struct Normals {
    pub normal: Vec3,
}

#[rt_function]
pub fn probe(top_object: Object, dir: Vec3) -> Vec3 {
    let mut p = Shadow { attenuation: Vec3::ONE };
    rt_trace(top_object, Ray::new(Vec3::ZERO, dir, 1, 0.001, f32::INFINITY), &mut p);
    p.attenuation
}

#[rt_program(any_hit)]
pub fn shadow(prd: &mut Shadow, attr: &Normals, #[var] top_object: Object) {
    prd.attenuation = probe(top_object, attr.normal);
}

fn main() {}
