//! Branching: `if`/`else` as a statement and as an expression (also with a
//! diverging branch), `else if` chains, early `return` from a program and
//! from a helper, blocks as expressions and as scopes, and `let` shadowing.
use super::seed_common::*;
use rt_std::prelude::*;

/// Buckets a value: an early return and an `else if` chain as the tail.
#[rt_function]
pub fn bucket(v: f32) -> i32 {
    if v < 0.0 {
        return -1;
    }
    if v == 0.0 {
        0
    } else if v < 1.0 {
        1
    } else if v < 10.0 {
        2
    } else {
        3
    }
}

#[rt_program(closest_hit)]
pub fn control_flow(prd: &mut Radiance, attr: &Normals, #[var] threshold: f32) {
    if prd.depth > 4 {
        prd.result = Vec3::ZERO;
        return;
    }
    let facing = attr.shading_normal.dot(-current_ray().direction);
    // Shadowing: each `facing` is a new binding.
    let facing = facing.max(0.0);
    let facing = facing * facing;
    let tint = if facing > threshold {
        vec3(1.0, 0.9, 0.8)
    } else if facing > 0.5 * threshold {
        Vec3::splat(0.5)
    } else {
        Vec3::ZERO
    };
    let inv_importance = if prd.importance <= 0.0 {
        prd.result = tint;
        return;
    } else {
        1.0 / prd.importance
    };
    let weight = {
        let k = bucket(facing - threshold);
        let base = k as f32 * 0.25;
        base + 0.125
    };
    let mut color = tint * weight * inv_importance;
    if color.x > 1.0 {
        color.x = 1.0;
    } else if color.y > 1.0 {
        color.y = 1.0;
    } else {
        color.z = color.z.min(1.0);
    }
    {
        let color = color * 0.5;
        prd.importance *= color.length();
    }
    prd.result = if prd.depth == 0 { color } else { color * 0.5 };
}
