//! The walk's two tests, one implementation per instruction set: a ray
//! against a node's eight boxes, and against a leaf's four triangles.
//!
//! Every implementation gives the same answers: the box test takes the
//! same operations in the same order (`(plane - origin) * inv_dir`, then
//! min/max with SSE's NaN rule: the second operand when either is NaN),
//! and the triangle test is [`WatertightRay::intersect`]'s, lane by lane.
//! So the forced paths (`RT_CPU_SIMD`) visit the same nodes and commit the
//! same hits.

pub(crate) mod scalar;
#[cfg(target_arch = "x86_64")]
pub(crate) mod x86;

use super::watertight::WatertightRay;
use super::{Node, PACKET, Packet, WIDTH};
use glam::Vec3;

/// The far distance of a box is scaled by this before it is compared,
/// so rounding in the slab test never culls a box the ray touches (pbrt's
/// `1 + 2 * gamma(3)`).
pub(crate) const FAR_SCALE: f32 = 1.0 + 2.0 * GAMMA3;

/// The near distance moves towards the origin by this fraction of itself
/// (`near - |near| * NEAR_SLACK`): rounding must not put a box's entry
/// beyond a hit in it at a shared edge, where the closest hit so far (a
/// neighbour, one ulp further) would then cull the closer one. Twice the
/// far side's margin, covering the triangle test's own rounding of `t`.
pub(crate) const NEAR_SLACK: f32 = 4.0 * GAMMA3;

/// pbrt's `gamma(3)`: the relative error bound of three roundings.
const GAMMA3: f32 = (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// A ray as the walk needs it, before an instruction set lays it out.
pub(crate) struct WalkRay<'a> {
    pub(crate) origin: Vec3,
    pub(crate) inv_dir: Vec3,
    pub(crate) tmin: f32,
    /// The triangle test's setup (None: a direction without a non-zero
    /// component, which hits no triangle).
    pub(crate) triangle: Option<&'a WatertightRay>,
}

impl WalkRay<'_> {
    /// The row of [`Node::planes`] holding the near plane on each axis
    /// (the far plane's is the other of its pair), by the sign bit of the
    /// inverse direction: a direction of -0 has an inverse of -inf and
    /// enters boxes through their high planes.
    pub(crate) fn near_rows(&self) -> [usize; 3] {
        let inv = self.inv_dir;
        let s = |c: f32| c.is_sign_negative() as usize;
        [s(inv.x), 2 + s(inv.y), 4 + s(inv.z)]
    }
}

/// The triangles of a packet a ray hits in `(tmin, tmax)`: lane bits in
/// `mask`, each lane's distance and barycentrics (weights of the second
/// and third vertex).
#[derive(Clone, Copy, Default)]
pub(crate) struct Hits {
    pub(crate) mask: u32,
    pub(crate) t: [f32; PACKET],
    pub(crate) u: [f32; PACKET],
    pub(crate) v: [f32; PACKET],
}

/// One instruction set's tests.
pub(crate) trait Kernels {
    /// The ray laid out for the tests (broadcast lanes).
    type Ray<'a>;
    fn ray<'a>(ray: &WalkRay<'a>) -> Self::Ray<'a>;
    /// The children of `node` the ray enters before `tmax`: a bit per
    /// child, and each child's entry distance.
    fn node(node: &Node, ray: &Self::Ray<'_>, tmax: f32) -> (u32, [f32; WIDTH]);
    /// The triangles of `packet` the ray hits before `tmax` (only called
    /// when the ray has a triangle setup).
    fn packet(packet: &Packet, ray: &Self::Ray<'_>, tmax: f32) -> Hits;
}

/// SSE's `maxps`/`minps` on one lane: `b` unless `a` is strictly beyond it,
/// so a NaN `a` (a ray in a slab's plane) leaves `b`.
#[inline(always)]
pub(crate) fn max_sse(a: f32, b: f32) -> f32 {
    if a > b { a } else { b }
}

#[inline(always)]
pub(crate) fn min_sse(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}
