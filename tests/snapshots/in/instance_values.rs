//! Instances: a closest hit that tints each instance of a mesh by its index
//! and marks those the host gave an id, and an any-hit program that lets
//! shadows through one instance id.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn tint_by_instance(prd: &mut Radiance, attr: &Normals) {
    let hue = (instance_index() % 8) as f32 / 8.0;
    let mut c = attr.shading_normal * 0.5 + Vec3::splat(hue);
    if instance_id() != INSTANCE_ID_NONE {
        c = c * 0.5;
    }
    prd.result = c;
}

#[rt_program(any_hit)]
pub fn glass_instance_passes(prd: &mut Shadow, #[var] glass_id: u32) {
    if instance_id() == glass_id {
        rt_ignore_intersection();
    }
    prd.attenuation = Vec3::ZERO;
}
