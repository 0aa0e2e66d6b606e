//! Bool vectors: glam's comparisons and masks of `Vec3`, `Vec4`, `IVec2`
//! and `UVec4` (WGSL's `vecN<bool>`), `BVec` locals and helper parameters
//! and results, their operators, `any`/`all`/`bitmask`, `BVecN::new`,
//! `splat` and `bvecN`, and `VecN::select` (WGSL's `select` with the
//! arguments the other way round). A buffer holds a mask's `bitmask()`.
use rt_std::prelude::*;

#[rt_function]
pub fn outside(p: Vec3, lo: Vec3, hi: Vec3) -> BVec3 {
    p.cmplt(lo) | p.cmpgt(hi)
}

#[rt_program(ray_generation)]
pub fn bool_vectors(#[var] p: Vec3, #[var] q: Vec4, #[var] i: IVec2, #[var] mut out: RwBuffer<UVec4>) {
    let away: BVec3 = outside(p, Vec3::ZERO, Vec3::ONE);
    let mut m = away ^ BVec3::new(true, false, true);
    m &= !p.is_nan_mask() & p.is_finite_mask();
    let signs = q.is_negative_mask() | q.cmpeq(Vec4::ZERO) & !BVec4A::splat(false);
    let c = Vec3::select(m, p, -p);
    let k =
        IVec2::select(i.cmpge(IVec2::ZERO) & bvec2(true, true), i, i.is_negative_mask().bitmask() as i32 * IVec2::ONE);
    let u = UVec4::splat(3).cmpne(uvec4(1, 3, 5, 3)) == bvec4(true, false, true, false);
    out[0] = uvec4(
        m.bitmask() | (signs.bitmask() << 3),
        away.any() as u32 + m.all() as u32 + u as u32,
        i.cmple(k).bitmask() + i.cmplt(k).bitmask() + i.cmpeq(k).bitmask(),
        Vec4::select(signs, q, Vec4::ONE).cmpne(q).bitmask() + c.cmpgt(p).bitmask(),
    );
}
