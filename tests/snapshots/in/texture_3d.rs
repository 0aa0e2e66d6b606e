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

/// `sample_grad` (OptiX `tex3DGrad`): the fog at the level of a pixel's
/// footprint (its derivatives from the launch width), through the variable
/// and through an id.
#[rt_program(miss)]
pub fn fog_footprint(
    prd: &mut Radiance,
    #[var] fog: Sampler3d,
    #[var] fog_id: BindlessSampler<Sampler3d>,
    #[var] bounds: Vec3,
) {
    let ray = current_ray();
    let uvw = (ray.origin + ray.direction) / bounds;
    let step = 1.0 / launch_dim().x as f32;
    let dx = vec3(step, 0.0, 0.0) / bounds;
    let dy = vec3(0.0, step, 0.0) / bounds;
    prd.result = fog.sample_grad(uvw, dx, dy).xyz() + fog_id.sample_grad(uvw, dx, dy).xyz();
}
