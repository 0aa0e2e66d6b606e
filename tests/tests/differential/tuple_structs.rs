//! Tuple structs: built as `Rgb(a, b, c)`, read by `.0`, destructured in
//! `let` and `match`, with `#[rt_impl]` methods, through helpers, and as
//! buffer elements the host writes.

use super::*;

/// A colour as three unnamed channels.
#[rt_struct(impl)]
pub struct Rgb(pub f32, pub f32, pub f32);

#[rt_impl]
impl Rgb {
    /// Rec. 709 luminance, by `self.0`...
    pub fn luminance(&self) -> f32 {
        0.2126 * self.0 + 0.7152 * self.1 + 0.0722 * self.2
    }

    /// A new value, built in a method.
    pub fn scaled(&self, k: f32) -> Rgb {
        Rgb(self.0 * k, self.1 * k, self.2 * k)
    }
}

/// Fields of two types, one a vector.
#[rt_struct]
pub struct Tagged(pub u32, pub Vec2);

impl Value for Rgb {
    fn comps(&self) -> Vec<Comp> {
        vec![Comp::F(self.0), Comp::F(self.1), Comp::F(self.2)]
    }
}

/// A tuple struct in and out of a helper, destructured.
#[rt_function]
pub fn brighter(c: Rgb) -> Rgb {
    let Rgb(r, g, mut b) = c;
    b *= 2.0;
    Rgb(r + 0.5, g, b)
}

differential! {
    /// Tuple structs as values and buffer elements.
    fn tuple_structs {
        /// Read from a buffer, built, read, destructured, matched, through
        /// methods and helpers, written out.
        values(c: Rgb, k: u32) -> [f32; 4] over pairs(&[Rgb(0.0, 0.5, 1.0), Rgb(2.0, -1.0, 0.25)], &[0, 1, 2, 3]), tol CHAINED => {
            let d = brighter(c).scaled(k as f32);
            let Rgb(r, _, b) = d;
            let mut t = Tagged(k, Vec2::new(r, b));
            t.1.y += 1.0;
            let m = match t {
                Tagged(0, v) => v.x,
                Tagged(1 | 2, v) => v.y,
                Tagged(_, _) => -1.0,
            };
            [d.luminance(), r + b, m, t.1.x + t.0 as f32]
        }
        /// Written to an output buffer of tuple structs.
        written(c: Rgb) -> [Rgb; 2] over one(&[Rgb(0.0, 0.5, 1.0), Rgb(2.0, -1.0, 0.25)]) => {
            let Rgb(r, g, b) = c;
            [Rgb(b, g, r), brighter(c)]
        }
    }
}
