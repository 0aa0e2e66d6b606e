//! glam's vectors and matrices as arrays (`to_array`, `to_cols_array`,
//! `to_cols_array_2d`, `to_rows_array`) on both backends, indexed at run
//! time.

use super::*;

differential! {
    /// Every element of each array, by a run-time index.
    fn glam_arrays {
        vector_arrays(a: Vec3, k: u32) -> [Vec4; 3] over pairs(&vec3s(8, 3.0, 71), &[0, 1, 2, 3]) => {
            let j = k as usize;
            let f = a.extend(-2.0).to_array();
            let i = (a * 10.0).as_ivec3().to_array();
            let u = uvec2(k, 7).to_array();
            [
                vec4(f[j], a.to_array()[j % 3], a.truncate().to_array()[j % 2], f[3 - j]),
                vec4(i[j % 3] as f32, u[j % 2] as f32, (a * 10.0).as_ivec3().extend(5).to_array()[j] as f32, 0.0),
                vec4(a.xy().as_uvec2().to_array()[j % 2] as f32, (a.as_ivec3().xy()).to_array()[1] as f32, 0.0, 0.0),
            ]
        }
        matrix_arrays(a: Mat3, k: u32) -> [Vec4; 3] over pairs(&mat3s(6, 72), &[0, 1, 2, 3]) => {
            let j = k as usize;
            let m4 = Mat4::from_cols(a.x_axis.extend(0.0), a.y_axis.extend(1.0), a.z_axis.extend(2.0), Vec4::W);
            let m2 = Mat2::from_cols(a.x_axis.truncate(), a.y_axis.truncate());
            let (c3, r3, g3) = (a.to_cols_array(), a.to_rows_array(), a.to_cols_array_2d());
            let (c4, r4, g4) = (m4.to_cols_array(), m4.to_rows_array(), m4.to_cols_array_2d());
            [
                vec4(c3[j * 2], r3[j * 2], g3[j % 3][2 - j % 3], c3[8 - j]),
                vec4(c4[j * 5], r4[j * 3 + 1], g4[j][3 - j], r4[15 - j]),
                vec4(m2.to_cols_array()[j], m2.to_rows_array()[j], m2.to_cols_array_2d()[j % 2][1 - j % 2], 0.0),
            ]
        }
    }
}
