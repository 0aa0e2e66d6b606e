//! The built-in attributes of a triangle hit (the watertight test itself
//! is [`crate::accel::wide::watertight`]'s).

use crate::scene::TriangleMesh;
use glam::{Vec2, Vec3};
use rt_std::cpu::{HIT_TRIANGLE_BACK, HIT_TRIANGLE_FRONT, Transforms, TriangleBuiltins};

/// The unnormalised geometric normal of the triangle with vertices `[a, b,
/// c]`: `(b - a) x (c - a)`.
///
/// The vertices come by reference: copied as an argument, they went through
/// the stack in stores and loads of other widths (a stall).
#[inline]
pub(crate) fn geometric_normal(&[a, b, c]: &[Vec3; 3]) -> Vec3 {
    (b - a).cross(c - a)
}

/// The built-in attributes of triangle `prim` of `mesh`, with geometric
/// normal `gn` ([`geometric_normal`]), hit at barycentrics `(u, v)`
/// (weights of vertices 1 and 2).
pub(crate) fn triangle_builtins(mesh: &TriangleMesh, prim: u32, gn: Vec3, u: f32, v: f32) -> TriangleBuiltins {
    let [i0, i1, i2] = mesh.indices[prim as usize].map(|i| i as usize);
    let w = 1.0 - u - v;
    let sn = match &mesh.normals {
        Some(n) => n[i0] * w + n[i1] * u + n[i2] * v,
        None => gn,
    };
    let uv = match &mesh.texcoords {
        Some(tc) => tc[i0] * w + tc[i1] * u + tc[i2] * v,
        None => Vec2::new(u, v),
    };
    TriangleBuiltins { geometric_normal: gn, shading_normal: sn, texcoord: uv, barycentrics: Vec2::new(u, v) }
}

/// The side of a triangle with geometric normal `normal` (in object space,
/// [`geometric_normal`]) a ray along world direction `d` meets, under
/// transforms `xf`: as the wgpu kernel's `rt_hit_kind` says, in the
/// instance's object space.
pub(crate) fn front_or_back(xf: Option<&Transforms>, normal: Vec3, d: Vec3) -> u32 {
    let d = xf.map_or(d, |x| (x.world_to_object * d.extend(0.0)).truncate());
    if d.dot(normal) < 0.0 { HIT_TRIANGLE_FRONT } else { HIT_TRIANGLE_BACK }
}
