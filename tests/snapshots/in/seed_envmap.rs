//! Example 6: the miss program samples a latitude/longitude environment map.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn envmap_miss(prd: &mut Radiance, #[var] envmap: Sampler2d) {
    let d = current_ray().direction;
    let theta = d.x.atan2(d.z);
    let phi = FRAC_PI_2 - d.y.acos();
    let u = (theta + PI) * (0.5 * FRAC_1_PI);
    let v = 0.5 * (1.0 + phi.sin());
    prd.result = envmap.sample(vec2(u, v)).xyz();
}
