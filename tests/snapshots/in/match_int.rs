//! `match` on integers: literal arms joined with `|`, negative literals,
//! `_` and binding catch-alls, as a statement (with an early return in an
//! arm) and as an expression (also inside arithmetic).
use super::seed_common::*;
use rt_std::prelude::*;

/// A material table written as a `match` expression.
#[rt_function]
pub fn material_albedo(id: u32) -> Vec3 {
    match id {
        0 => vec3(0.8, 0.8, 0.8),
        1 | 2 => vec3(0.9, 0.1, 0.1),
        4 | 7 | 9 => vec3(0.1, 0.9, 0.1),
        _ => Vec3::new(0.1, 0.1, 0.9),
    }
}

#[rt_program(closest_hit)]
pub fn match_int(prd: &mut Radiance, attr: &Normals, #[var] material: u32) {
    let mut color = material_albedo(material);
    match prd.depth {
        0 => {}
        1 | 2 => color *= 0.5,
        -1 => {
            prd.result = Vec3::ZERO;
            return;
        }
        _ => {
            color *= 0.25;
        }
    }
    let bounce_weight = 1.0
        + match prd.depth {
            0 => 0.0,
            d => 1.0 / d as f32,
        };
    let lobe: i32 = match primitive_index() % 4 {
        0 => 1,
        1 | 3 => -1,
        other => other as i32 * 2,
    };
    let n = attr.shading_normal * lobe as f32;
    prd.result = color * bounce_weight * n.z.abs();
}
