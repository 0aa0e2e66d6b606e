//! glam's `to_array` of the vectors and `to_cols_array`,
//! `to_cols_array_2d`, `to_rows_array` of the matrices: WGSL arrays built
//! from the components (a receiver that is more than a name is read once,
//! into a `let`).
use rt_std::prelude::*;

#[rt_program(ray_generation)]
pub fn glam_arrays(#[var] v: Vec3, #[var] i: IVec2, #[var] m: Mat3, #[var] k: u32, #[var] mut out: RwBuffer<f32>) {
    let a = v.to_array();
    let b = (i * 2).to_array();
    let c = uvec4(1, 2, 3, k).to_array();
    let cols = m.to_cols_array();
    let rows = (m * 2.0).to_rows_array();
    let grid = Mat2::IDENTITY.to_cols_array_2d();
    let big = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::Z, v.extend(1.0)).to_cols_array();
    let j = (k % 3) as usize;
    out[0] = a[j] + b[j % 2] as f32 + c[j] as f32 + cols[j * 3] + rows[j + 1] + grid[j % 2][1] + big[12 + j];
}
