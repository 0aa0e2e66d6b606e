// A bounding-box program runs at build time: it cannot call callables.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn bounds(prim: u32, #[var] radius: Callable<fn(u32) -> f32>) -> Aabb {
    let r = radius.call(prim);
    Aabb::new(Vec3::splat(-r), Vec3::splat(r))
}

fn main() {}
