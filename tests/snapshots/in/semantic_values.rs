//! The semantic values of a hit and of a ray: which side of a triangle an
//! any-hit program sees (ignoring back faces of shadow casters), and a
//! closest hit and a miss that read the ray's flags and mask.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(any_hit)]
pub fn front_faces_cast(prd: &mut Shadow) {
    if is_triangle_hit() && is_triangle_hit_back_face() && (ray_flags() & RAY_FLAG_CULL_BACK_FACING) == 0 {
        rt_ignore_intersection();
    }
    prd.attenuation = Vec3::ZERO;
}

#[rt_program(closest_hit)]
pub fn tint_by_side(prd: &mut Radiance, attr: &Normals) {
    let mut c = attr.shading_normal * 0.5 + Vec3::splat(0.5);
    if is_triangle_hit_front_face() {
        c = c * 0.5;
    }
    if ray_mask() != RAY_MASK_ALL {
        c = Vec3::ONE - c;
    }
    prd.result = c;
}

#[rt_program(miss)]
pub fn flags_shown(prd: &mut Radiance) {
    prd.result = Vec3::new(ray_flags() as f32, ray_mask() as f32, 0.0) / 255.0;
}
