//! Example 1: the pinhole camera, the background and the exception program.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn pinhole_camera(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] scene_epsilon: f32,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let idx = launch_index();
    let dim = launch_dim();
    let d = (idx.as_vec2() + Vec2::splat(0.5)) / dim.as_vec2() * 2.0 - Vec2::ONE;
    let ray_direction = (d.x * u + d.y * v + w).normalize();
    let ray = Ray::new(eye, ray_direction, RADIANCE_RAY, scene_epsilon, f32::INFINITY);
    let mut prd = Radiance { result: Vec3::ZERO, importance: 1.0, depth: 0 };
    rt_trace(top_object, ray, &mut prd);
    output_buffer[idx] = prd.result.extend(1.0);
}

#[rt_program(miss)]
pub fn miss(prd: &mut Radiance, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

#[rt_program(exception)]
pub fn exception(#[var] bad_color: Vec3, #[var] mut output_buffer: RwBuffer2d<Vec4>) {
    let code = exception_code();
    rt_printf!("exception {} at {}", code, launch_index());
    output_buffer[launch_index()] = bad_color.extend(1.0);
}
