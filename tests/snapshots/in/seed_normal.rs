//! Example 1: the normal shader.
use rt_std::prelude::*;
use super::seed_common::*;

#[rt_program(closest_hit)]
pub fn closest_hit_radiance(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
}
