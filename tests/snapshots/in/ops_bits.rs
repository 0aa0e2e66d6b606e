//! Bit manipulation as hash functions use it: `& | ^ !` on `u32` and `i32`,
//! shifts by literals and by variables of either signedness (arithmetic on
//! `i32`), every compound bit assignment, the bit-count methods and
//! wrapping arithmetic.
use rt_std::prelude::*;

/// The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering").
#[rt_function]
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

#[rt_program(ray_generation)]
pub fn ops_bits(
    #[var] seed: u32,
    #[var] signed_seed: i32,
    #[var] shift: i32,
    #[var] out_u: RwBuffer<u32>,
    #[var] out_i: RwBuffer<i32>,
) {
    let idx = launch_index();
    let pixel = idx.y * launch_dim().x + idx.x;
    let h = pcg_hash(pixel ^ seed);

    let mut bits = h & 0xffff;
    bits |= 1 << 31;
    bits ^= seed;
    bits &= !0xf0u32;
    bits <<= 3;
    bits >>= 1u32;
    bits <<= shift;
    let packed = (h >> 24) | ((h & 0xff) << 8) | (!h & 0xff0000);
    let count = bits.count_ones() + packed.leading_zeros() + h.trailing_zeros();
    out_u.store(pixel, bits ^ packed.reverse_bits() ^ count.wrapping_sub(1));

    let mut s = signed_seed;
    s >>= 2;
    s <<= shift as u32;
    s |= -16;
    s &= !(1 << 3);
    s ^= 0x55;
    let t = (s >> shift) & (s << 1) | !s ^ (s >> 31u32);
    let ones = s.count_ones() as i32 - s.leading_zeros() as i32 + s.trailing_zeros() as i32;
    out_i.store(pixel, t.wrapping_add(ones).wrapping_mul(3).abs() + s.reverse_bits().signum());
}
