// rt_trace may be called from ray generation, closest hit and miss only.
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
pub fn shadow(prd: &mut Shadow, attr: &Normals, #[var] top_object: Object) {
    let ray = Ray::new(Vec3::ZERO, attr.normal, 1, 0.001, f32::INFINITY);
    let mut probe = Shadow { attenuation: Vec3::ONE };
    rt_trace(top_object, ray, &mut probe);
    prd.attenuation = probe.attenuation;
}

fn main() {}
