//! The dividing methods of the integers (`div_euclid`, `rem_euclid`,
//! `wrapping_div`, `saturating_div`) on `i32`, `u32` and their vectors,
//! with constant operands too: each is a function of the module whose
//! divisor is made safe first (a zero divisor is read as one,
//! `i32::MIN / -1` does not overflow), so WGSL never sees a constant zero
//! divisor.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn int_division(#[var] a: i32, #[var] b: u32, #[var] v: IVec3, #[var] mut out: RwBuffer<IVec4>) {
    let q = a.div_euclid(-3) + a.rem_euclid(0) + i32::MIN.wrapping_div(-1) + a.saturating_div(a);
    let u = b.div_euclid(0) + u32::rem_euclid(7, b) + b.wrapping_div(2) + b.saturating_div(b);
    let w = v.div_euclid(IVec3::ZERO) + v.rem_euclid(ivec3(2, -2, 0)) + IVec3::MIN.saturating_div(-IVec3::ONE);
    let x = uvec2(b, 9).wrapping_div(UVec2::ZERO) + UVec2::splat(b).saturating_div(uvec2(3, 0));
    let y =
        ivec4(a, 1, 2, 3).wrapping_div(IVec4::splat(a)) + IVec2::new(a, 5).div_euclid(ivec2(0, -2)).extend(0).extend(1);
    out[0] = y + w.extend(q + u as i32 + x.x as i32);
}
