//! Every `as` cast between the scalar types Rust allows: float to integer
//! (truncating, saturating), integer to float, between `i32` and `u32`
//! (bit-preserving), through `usize` (array indices), and `bool` to
//! integers.
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn casts(
    #[var] f: f32,
    #[var] i: i32,
    #[var] u: u32,
    #[var] flag: bool,
    #[var] table: Buffer<f32>,
    #[var] out_f: RwBuffer<f32>,
    #[var] out_i: RwBuffer<i32>,
    #[var] out_u: RwBuffer<u32>,
) {
    let slot = launch_index().x;
    let from_f_i = f as i32;
    let from_f_u = f as u32;
    let from_f_z = f as usize;
    let from_i_f = i as f32;
    let from_i_u = i as u32;
    let from_i_z = i as usize;
    let from_u_f = u as f32;
    let from_u_i = u as i32;
    let from_u_z = u as usize;
    let from_z_f = from_i_z as f32;
    let from_z_i = from_u_z as i32;
    let from_z_u = from_f_z as u32;
    let from_b_i = flag as i32;
    let from_b_u = flag as u32;
    let from_b_z = flag as usize;
    let weights = [0.5f32, 0.25, 0.125, 0.0625];
    let picked = weights[(u % 4) as usize] + weights[from_b_z] + weights[from_u_z % 4];
    let sum = from_i_f + from_u_f + from_z_f + picked + table[from_z_u] + (slot / 2) as f32;
    out_f.store(slot, sum);
    out_i.store(slot, from_f_i + from_u_i + from_z_i + from_b_i + (sum * 0.5) as i32 + (u >> 1) as i32);
    out_u.store(slot, from_f_u + from_i_u + from_b_u + ((from_i_z + from_f_z) as u32) + (-f) as u32);
}
