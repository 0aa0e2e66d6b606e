// A bounding-box program sampling through a bindless sampler id: it runs
// at build time, outside any launch.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn bounds(prim: u32, #[var] heights: BindlessSampler<Sampler2d>) -> Aabb {
    let h = heights.sample(vec2(prim as f32, 0.0)).x;
    Aabb::new(Vec3::ZERO, vec3(1.0, h, 1.0))
}

fn main() {}
