//! Cube maps: `SamplerCube::sample_dir` with the ray's direction and a
//! reflected one, and `size`, in a miss program (an environment cube).
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(miss)]
pub fn cube_miss(prd: &mut Radiance, #[var] sky: SamplerCube, #[var] ground: SamplerCube) {
    let d = current_ray().direction;
    let mut c = sky.sample_dir(d).xyz();
    if d.y < 0.0 {
        c = c * 0.5 + ground.sample_dir(reflect(d, Vec3::Y)).xyz() / ground.size() as f32;
    }
    prd.result = c;
}

/// Mip levels: `sample_dir_lod` at a LOD from a roughness and the level
/// count, and a 3D texture's `sample_lod` and `levels` through an id.
#[rt_program(miss)]
pub fn blurred_sky(
    prd: &mut Radiance,
    #[var] sky: SamplerCube,
    #[var] fog: BindlessSampler<Sampler3d>,
    #[var] roughness: f32,
) {
    let d = current_ray().direction;
    let lod = roughness * (sky.levels() - 1) as f32;
    prd.result = sky.sample_dir_lod(d, lod).xyz() * fog.sample_lod(d * 0.5 + 0.5, lod).w / fog.levels() as f32;
}
