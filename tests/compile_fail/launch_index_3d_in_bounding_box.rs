// Bounding boxes are computed while the acceleration structure is built,
// outside any launch index.
use rt_std::prelude::*;

#[rt_program(bounding_box)]
pub fn bounds(prim: u32) -> Aabb {
    let z = launch_index_3d().z as f32;
    Aabb::new(Vec3::splat(prim as f32), Vec3::splat(z))
}

fn main() {}
