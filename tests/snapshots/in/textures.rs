//! Textures: `Sampler2d::sample` with filtered normalised coordinates,
//! `fetch` of single texels, and `size`, in a closest-hit program that
//! shades a triangle mesh from its barycentrics and a normal map.
use super::seed_common::*;
use rt_std::prelude::*;

/// What the mesh intersection reports.
#[rt_attributes]
pub struct MeshHit {
    pub normal: Vec3,
    pub uv: Vec2,
}

#[rt_program(closest_hit)]
pub fn textures(
    prd: &mut Radiance,
    attr: &MeshHit,
    #[var] albedo: Sampler2d,
    #[var] normal_map: Sampler2d,
    #[var] palette: Sampler2d,
    #[var] tiling: f32,
) {
    let uv = attr.uv * tiling;
    let base = albedo.sample(uv);
    let texel = (uv.fract() * normal_map.size().as_vec2()).as_uvec2();
    let bump = normal_map.fetch(texel).xyz() * 2.0 - 1.0;
    let n = (attr.normal + bump * 0.25).normalize();
    let last = palette.size() - 1;
    let entry = palette.fetch(uvec2(primitive_index() % (last.x + 1), last.y));
    let light = n.dot(vec3(0.0, 1.0, 0.0)).max(0.0);
    prd.result = base.xyz() * entry.xyz() * light * base.w;
}
