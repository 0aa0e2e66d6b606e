//! 3D textures: `Sampler3d::sample` at a point of the ray, `fetch` of a
//! voxel and `size`, in a miss program (a fog volume).
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn fog_miss(prd: &mut Radiance, #[var] fog: Sampler3d, #[var] bounds: Vec3) {
    let ray = current_ray();
    let uvw = (ray.origin + ray.direction) / bounds;
    let density = fog.sample(uvw).x;
    let last = fog.size() - 1;
    let corner = fog.fetch(uvec3(last.x, 0, last.z));
    prd.result = corner.xyz() * density;
}
