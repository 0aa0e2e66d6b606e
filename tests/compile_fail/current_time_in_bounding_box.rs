// A bounding-box program runs at acceleration build time, not for a ray:
// there is no ray time to read.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn moving_bounds(prim: u32) -> Aabb {
    let _ = prim;
    let x = current_time();
    Aabb::new(Vec3::splat(-1.0 + x), Vec3::splat(1.0 + x))
}

fn main() {}
