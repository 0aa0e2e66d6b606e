//! glam's in-place methods: `set_row` and `col_mut` of a matrix (a local and a `&mut`
//! parameter) and `set`/`test` of a bool vector, as assignments to the
//! receiver's place with the index clamped to the last row or component.
use rt_std::prelude::*;

#[rt_function]
pub fn put_row(m: &mut Mat3, i: u32, v: Vec3) {
    m.set_row(i as usize, v);
}

#[rt_program(ray_generation)]
pub fn glam_in_place(#[var] v: Vec4, #[var] k: u32, #[var] mut out: RwBuffer<f32>) {
    let mut m = Mat4::IDENTITY;
    m.set_row(k as usize, v);
    let mut n = Mat3::ZERO;
    put_row(&mut n, k + 1, v.truncate());
    *m.col_mut(k as usize) += v;
    n.col_mut(2).y = v.x;
    let mut mask = v.cmpgt(Vec4::ZERO);
    mask.set(k as usize, false);
    out[0] = m.w_axis.y + n.z_axis.x + mask.bitmask() as f32 + mask.test(3) as u32 as f32;
}
