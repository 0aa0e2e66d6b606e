//! `#[rt_enum]`s: as inputs, outputs, locals, struct fields, helper
//! parameters and results, compared, cast and matched exhaustively; and as
//! variables the host sets by the Rust value.

use super::*;

/// Implicit discriminants (0, 1, 2).
#[rt_enum]
pub enum Shape {
    Sphere,
    Cube,
    Torus,
}

/// Explicit ones, none of them 0.
#[rt_enum]
#[repr(u32)]
pub enum Channel {
    Red = 2,
    Green = 7,
    Blue = 9,
}

impl Value for Shape {
    fn comps(&self) -> Vec<Comp> {
        vec![Comp::I(*self as u32 as i64)]
    }
}

impl Value for Channel {
    fn comps(&self) -> Vec<Comp> {
        vec![Comp::I(*self as u32 as i64)]
    }
}

/// A struct with an enum field.
#[rt_struct]
pub struct Tagged {
    pub shape: Shape,
    pub scale: f32,
}

/// An exhaustive `match` on a parameter, as the function's value.
#[rt_function]
pub fn volume(s: Shape, r: f32) -> f32 {
    match s {
        Shape::Sphere => 4.18879 * r * r * r,
        Shape::Cube => 8.0 * r * r * r,
        Shape::Torus => 4.9348 * r * r,
    }
}

/// An enum from an integer, returned.
#[rt_function]
pub fn shape_of(code: u32) -> Shape {
    match code % 3 {
        0 => Shape::Sphere,
        1 => Shape::Cube,
        _ => Shape::Torus,
    }
}

const SHAPES: [Shape; 3] = [Shape::Sphere, Shape::Cube, Shape::Torus];

differential! {
    /// Enums in and out of buffers, through helpers, structs and matches.
    fn enums_as_values {
        /// Returned from a helper, compared, assigned, written out.
        from_codes(code: u32) -> [Shape; 2] over one(&u64_grid()) => {
            let s = shape_of(code);
            let mut t = s;
            if t == Shape::Torus {
                t = Shape::Sphere;
            }
            [s, t]
        }
        /// Read from a buffer, in a struct field, matched with `|`, cast.
        enum_inputs(s: Shape, r: f32) -> [f32; 3] over pairs(&SHAPES, &spread(16, 0.0, 2.0)), tol CHAINED => {
            let tagged = Tagged { shape: s, scale: r };
            let code = match tagged.shape {
                Shape::Sphere => 10,
                Shape::Cube | Shape::Torus => 20,
            };
            let half = if s != Shape::Cube { 0.5 } else { 0.0 };
            [volume(tagged.shape, tagged.scale), code as f32, (s as u32) as f32 + half]
        }
        /// Explicit discriminants: `as u32` is the discriminant.
        explicit(c: Channel) -> [u32; 2] over one(&[Channel::Red, Channel::Green, Channel::Blue]) => {
            let next = match c {
                Channel::Red => Channel::Green,
                Channel::Green => Channel::Blue,
                Channel::Blue => Channel::Red,
            };
            [c as u32, next as u32 * 100 + (next == Channel::Red) as u32]
        }
    }
}

#[rt_program(ray_generation)]
pub fn enum_variable(#[var] shape: Shape, #[var] channel: Channel, #[var] mut out: RwBuffer<u32>, #[var] top: Object) {
    let idx = launch_index().x;
    keep_scene_binding(top, idx);
    out[idx] = match shape {
        Shape::Sphere => 1u32,
        Shape::Cube => 2,
        Shape::Torus => 3,
    } * 100
        + channel as u32;
}

/// The host sets enum variables by value; a variable of another type is a
/// link error naming both types.
#[test]
fn enum_variables_are_set_from_the_host() {
    let mut h = Harness::new();
    for ctx in std::iter::once(&mut h.cpu).chain(&mut h.gpus) {
        let backend = (ctx.backend(), ctx.traversal_setting());
        let p = ctx.create_program(&enum_variable::PROGRAM);
        let out = ctx.create_buffer(BufferType::Output, vec![0u32; 1]);
        ctx.set_var(p, "out", out).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        for (shape, channel, want) in
            [(Shape::Sphere, Channel::Blue, 109), (Shape::Cube, Channel::Red, 202), (Shape::Torus, Channel::Green, 307)]
        {
            ctx.set_var(p, "shape", shape).unwrap();
            ctx.set_var(Scope::Context, "channel", channel).unwrap();
            ctx.launch(0, 1, 1).unwrap_or_else(|e| panic!("{backend:?}: {e}"));
            assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), vec![want], "{backend:?}");
        }
        ctx.set_var(p, "shape", 2u32).unwrap();
        let e = ctx.launch(0, 1, 1).unwrap_err().to_string();
        assert!(e.contains("Shape") && e.contains("u32"), "{backend:?}: {e}");
    }
}
