//! Rust that the compiler rewrites into plain loops and `if` chains before
//! it lowers a function: closures (bound, given to a helper and to a
//! method), iterator chains, `Option` flows, patterns, labelled loops,
//! a type alias, a tuple struct and a function declared in a body.
use rt_std::prelude::*;

/// A colour, by its alias.
#[rt_type]
pub type Tint = Vec3;

/// A tuple struct.
#[rt_struct]
pub struct Weights(pub f32, pub f32);

/// A range of distances whose method takes a closure.
#[rt_struct(impl)]
pub struct Depths {
    pub near: f32,
    pub far: f32,
}

#[rt_impl]
impl Depths {
    /// `f` at both ends, summed.
    pub fn at_ends<F: Fn(f32) -> f32>(&self, f: F) -> f32 {
        f(self.near) + f(self.far)
    }
}

/// Calls `f` twice.
#[rt_function]
pub fn twice_of<F: Fn(f32) -> f32>(f: F, x: f32) -> f32 {
    let once = f(x);
    f(once)
}

#[rt_program(ray_generation)]
pub fn sugar_gen(#[var] mut sugar_out: RwBuffer<f32>, #[var] sugar_k: f32) {
    let i = launch_index().x;
    let x = i as f32;
    // Closures: bound and called, given to a helper, given to a method.
    let scale = |v: f32| v * sugar_k;
    let span = Depths { near: x, far: x + 1.0 };
    let mut acc = scale(x) + twice_of(|v| v + sugar_k, x) + span.at_ends(|d| d * d);
    // Iterator chains over a fixed array and a range.
    let ws = [0.25, 0.5, 0.75];
    acc += ws.iter().enumerate().map(|(j, w)| w * j as f32).sum::<f32>();
    acc += (0..8u32).step_by(2).rev().fold(0.0, |a, j| a + j as f32);
    if ws.iter().any(|w| *w > x) {
        acc += 1.0;
    }
    // `Option`: built, matched, reduced.
    let first = if i % 2 == 0 { Some(x) } else { None };
    if let Some(f) = first {
        acc += f;
    }
    acc += first.map(|f| f * 2.0).unwrap_or(0.5);
    let Some(g) = first.filter(|f| *f > 1.0) else {
        sugar_out[i] = acc;
        return;
    };
    // Patterns: a range, `|`, a guard, `matches!`.
    acc += match i {
        0..=3 => g,
        4 | 5 => -g,
        n if n > 100 => 0.0,
        _ => 1.0,
    };
    if matches!(i % 4, 1 | 3) {
        acc *= 0.5;
    }
    // A labelled loop left from inside another, and `break` with a value.
    let mut found = 0u32;
    'rows: for r in 0..4u32 {
        for c in 0..4u32 {
            if r * c > i {
                found = r;
                break 'rows;
            }
        }
    }
    let mut n = 0u32;
    let steps = loop {
        n += 1;
        if n > found {
            break n * 2;
        }
    };
    // An alias, a tuple struct, a function declared in the body.
    let tint: Tint = Tint::splat(acc);
    let Weights(wa, wb) = Weights(0.5, 0.25);
    fn sugar_blend(a: f32, b: f32, t: f32) -> f32 {
        a + (b - a) * t
    }
    sugar_out[i] = sugar_blend(tint.x, steps as f32, wa) + wb;
}
