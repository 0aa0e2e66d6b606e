//! `rt_printf!` with no arguments, with scalars of every type (`bool`
//! included), with vectors, with `{{`/`}}` escapes, and from a helper.
use super::seed_common::*;
use rt_std::prelude::*;

/// Prints where a ray went; callable from any program kind.
#[rt_function]
pub fn log_ray(tag: u32, ray: Ray) {
    rt_printf!("ray {} from {} dir {}", tag, ray.origin, ray.direction);
}

#[rt_program(miss)]
pub fn printf(prd: &mut Radiance, #[var] verbose: bool) {
    let ray = current_ray();
    rt_printf!("miss");
    rt_printf!("depth {} importance {} verbose {}", prd.depth, prd.importance, verbose);
    if verbose {
        log_ray(ray.ray_type, ray);
        rt_printf!("{{raw}} {} {} {}", launch_index(), ivec3(-1, 0, 1), ray.tmax > 1.0);
    }
    prd.result = Vec3::ZERO;
}
