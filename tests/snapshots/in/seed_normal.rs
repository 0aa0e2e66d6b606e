//! Example 1: the normal shader.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn closest_hit_radiance(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
}
