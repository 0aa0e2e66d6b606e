//! Names the compiler must not read by their spelling: types whose names
//! are all capitals (`RGB`, `K3`, an enum `BRDF`, a payload `P`), a
//! constant in CamelCase, and a loop index whose type a later use decides
//! after a cast has read it.

// The capitals are the point of these names.
#![allow(clippy::upper_case_acronyms)]

use super::*;

#[rt_struct]
pub struct RGB {
    pub r: f32,
    pub g: f32,
    pub b: f32,
}

#[rt_struct]
pub struct K3 {
    pub k: [u32; 3],
}

#[rt_enum]
pub enum BRDF {
    Lambert,
    Mirror,
}

#[rt_payload]
pub struct P {
    pub color: Vec3,
}

#[rt_const]
#[allow(non_upper_case_globals)]
pub const Gain: f32 = 2.0;

/// A helper taking and returning capitalised types.
#[rt_function]
pub fn luminance(c: RGB, brdf: BRDF) -> f32 {
    let sign = match brdf {
        BRDF::Lambert => 1.0,
        BRDF::Mirror => -1.0,
    };
    (c.r * 0.25 + c.g * 0.5 + c.b * 0.25) * Gain * sign
}

/// A closest hit whose payload is named `P`.
#[rt_program(closest_hit)]
pub fn shade_p(prd: &mut P) {
    prd.color = Vec3::splat(Gain);
}

#[test]
fn a_payload_named_p_compiles_as_any_other() {
    let payload = shade_p::PROGRAM.payload.expect("a payload");
    assert_eq!((payload.rust, payload.words), ("P", 3));
}

differential! {
    /// Capitalised type names and a CamelCase constant.
    fn names_by_position_not_spelling {
        /// `RGB`, `K3` and `BRDF` as types, `Gain` as a constant.
        capitals(a: u32) -> [f32; 3] over one(&[0, 1, 2, 7, 100]) => {
            let c = RGB { r: a as f32, g: 1.0, b: 0.5 };
            let k = K3 { k: [a, a + 1, a + 2] };
            let brdf = if a % 2 == 0 { BRDF::Lambert } else { BRDF::Mirror };
            [luminance(c, brdf), k.k[2] as f32, Gain]
        }
        /// A range's index read by `as f32` before `b + j` makes it `u32`.
        index_typed_by_a_later_use(b: u32) -> [u32; 2] over one(&[0, 5, 1 << 20, 1 << 31]) => {
            let mut s = 0.0;
            let mut t = 0u32;
            for j in 0..4 {
                s += j as f32;
                t = t.wrapping_add(b + j);
            }
            [s as u32, t]
        }
    }
}
