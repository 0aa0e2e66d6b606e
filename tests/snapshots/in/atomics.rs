//! Atomic updates of buffer elements: a receiver grid that counts the
//! rays reaching each cell (u32 add), the energy they carry (f32 add, a
//! compare-exchange loop) and the nearest arrival (f32 min); a signed
//! extreme, the bitwise updates and a strong compare-exchange on a 2D
//! buffer.
use super::seed_common::*;
use rt_std::prelude::*;

#[rt_program(closest_hit)]
pub fn receiver_cell(
    prd: &mut Radiance,
    #[var] hits: RwBuffer2d<u32>,
    #[var] energy: RwBuffer2d<f32>,
    #[var] nearest: RwBuffer<f32>,
    #[var] cells: u32,
) {
    let p = current_ray().origin + current_ray().direction * t_hit();
    let cell = (p.xy() * 0.5 + Vec2::splat(0.5)) * cells as f32;
    let at = uvec2(cell.x as u32, cell.y as u32);
    hits.atomic_add(at, 1);
    energy.atomic_add(at, prd.importance);
    nearest.atomic_min(0, t_hit());
    prd.result = Vec3::ONE;
}

#[rt_program(ray_generation)]
pub fn flags_and_claims(#[var] signed: RwBuffer<i32>, #[var] mut bits: RwBuffer<u32>, #[var] owners: RwBuffer2d<u32>) {
    let i = launch_index();
    let v = i.x as i32 - i.y as i32;
    let lowest = signed.atomic_min(0, v);
    signed.atomic_max(1, v);
    signed.atomic_sub(2, v);
    bits.atomic_or(0, 1u32 << (i.x % 32));
    bits.atomic_and(1, !(1u32 << (i.y % 32)));
    bits.atomic_xor(2, i.x);
    bits[3] = bits.atomic_exchange(4, i.y) + lowest as u32;
    owners.atomic_compare_exchange(i / 8u32, 0u32, i.x + 1);
}
