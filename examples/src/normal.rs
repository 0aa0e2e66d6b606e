//! Example 1: the normal shader. The closest-hit program writes the
//! world-space shading normal as a colour; rays that miss see `bg_color`.

use crate::common::*;
use crate::scene::{Error, Scene, Settings};
use crate::tutorial::{self, Materials};
use rt_std::prelude::*;

/// `normalize(transform_normal(object->world, shading_normal)) * 0.5 + 0.5`.
#[rt_program(closest_hit)]
pub fn normal_shader(prd: &mut Radiance, attr: &Normals) {
    prd.result = rt_transform_normal(ObjectToWorld, attr.shading_normal).normalize() * 0.5 + 0.5;
}

/// The tutorial scene, every object normal-shaded.
pub fn scene(settings: &Settings) -> Result<Scene, Error> {
    let (mut ctx, output) = tutorial::start(settings)?;
    let materials = Materials::with_closest_hit(&mut ctx, &normal_shader::PROGRAM)?;
    tutorial::build(&mut ctx, materials)?;
    Ok(Scene::new(ctx, output, settings))
}
