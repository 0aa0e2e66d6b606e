//! Type aliases: `#[rt_type]` aliases of a glam type, a scalar, an array,
//! an enum, a struct of the program's own, a generic struct (with a parameter) and
//! another alias, named in signatures, fields, casts, before `::` and in
//! struct literals and patterns; and an alias declared in a body. Each use
//! stands for the type, as in Rust.
//!
//! (A braced struct pattern, `let Span { lo, .. } = s;`, is refused by
//! name or by alias alike: the subset has none.)

use super::*;
use crate::generic_structs::Pair;

/// A colour is a vector.
#[rt_type]
pub type Color = Vec3;

/// An alias of an alias.
#[rt_type]
pub type Tint = Color;

/// A scalar.
#[rt_type]
pub type Weight = f32;

/// An array.
#[rt_type]
pub type Quad = [Weight; 4];

/// An interval, named below by an alias.
#[rt_struct(impl)]
pub struct Interval {
    pub lo: f32,
    pub hi: f32,
}

#[rt_impl]
impl Interval {
    pub fn width(&self) -> f32 {
        self.hi - self.lo
    }
}

/// An alias of a struct of the program's own.
#[rt_type]
pub type Span = Interval;

/// An alias of an enum, matched by it.
#[rt_type]
pub type Form = crate::enums::Shape;

/// An alias with a type parameter, of a generic struct named by its path.
#[rt_type]
pub type Both<T> = crate::generic_structs::Pair<T>;

/// A struct whose fields are named by aliases.
#[rt_struct]
pub struct Lit {
    pub c: Tint,
    pub w: Weight,
}

/// An alias in a helper's signature, before `::` and in a literal.
#[rt_function]
pub fn dimmed(c: Color, w: Weight) -> Lit {
    Lit { c: c * w + Color::ZERO, w }
}

differential! {
    /// Aliases named everywhere a type is.
    fn aliases {
        /// Through helpers, fields, literals, patterns and casts.
        uses(a: f32, k: u32) -> [f32; 4] over pairs(&[0.5, -1.25, 3.0], &[0, 1, 2]), tol CHAINED => {
            let lit = dimmed(Color::new(a, 1.0, 2.0), k as Weight);
            let s = Span { lo: a, hi: a + k as f32 };
            let lo = match Form::Cube {
                Form::Sphere => 0.0,
                Form::Cube | Form::Torus => s.lo,
            };
            let q: Quad = [lit.c.x, lit.w, s.width(), lo];
            let p: Both<f32> = Pair { a: q[0], b: q[2] };
            let t = Tint::splat(p.a + p.b);
            type Local = Vec2;
            let v = Local::new(t.x, lit.c.z);
            [q[0] + q[1], q[2] + q[3], v.x, v.y]
        }
    }
}
