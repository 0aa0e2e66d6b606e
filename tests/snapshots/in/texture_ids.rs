//! Bindless textures: a closest hit samples the albedo of its instance's
//! material through a sampler id from a buffer of structs (`sample`,
//! `sample_lod`, `sample_grad`, `size`, `levels`), each read of a record
//! `rt_texid` checks against the launch's sampler table once; a miss
//! samples a cube map and a 3D texture through ids held in variables, and
//! compares ids.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_struct]
pub struct TexturedMaterial {
    pub albedo: BindlessSampler<Sampler2d>,
    pub roughness: f32,
}

#[rt_program(closest_hit)]
pub fn albedo_by_material(prd: &mut Radiance, #[var] material: u32, #[var] materials: Buffer<TexturedMaterial>) {
    let m = materials[material];
    let uv = vec2(t_hit() * 0.1, m.roughness);
    let base = m.albedo.sample(uv);
    let blurred = m.albedo.sample_lod(uv, m.roughness * m.albedo.levels() as f32);
    let texel = vec2(1.0, 1.0) / m.albedo.size().as_vec2();
    let filtered = m.albedo.sample_grad(uv, vec2(texel.x, 0.0), vec2(0.0, texel.y));
    prd.result = (base + blurred + filtered).xyz() / 3.0;
}

#[rt_program(miss)]
pub fn sky_by_id(prd: &mut Radiance, #[var] sky: BindlessSampler<SamplerCube>, #[var] fog: BindlessSampler<Sampler3d>) {
    let d = current_ray().direction;
    let mut c = sky.sample_dir(d).xyz();
    if sky != BindlessSampler::NONE && fog.id() != 0 {
        c = c * fog.sample(d * 0.5 + 0.5).w / sky.size() as f32;
    }
    prd.result = c;
}
