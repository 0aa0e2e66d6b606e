//! `#[rt_trait]`s with static dispatch: trait impls for structs (one with
//! an inherent block too), a default method and a default associated
//! constant, an override of each, calls resolved by the receiver's type,
//! and generic helpers bounded by the trait.

use super::*;

/// A reflectance model.
#[rt_trait]
pub trait Reflect {
    /// Scales what `eval` gives.
    const GAIN: f32 = 1.0;
    fn albedo(&self) -> f32;
    /// A default method calling a required one and the constant.
    fn eval(&self, c: f32) -> f32 {
        self.albedo() * c * Self::GAIN
    }
}

#[rt_struct(impl Reflect)]
pub struct Matte {
    pub a: f32,
}

#[rt_struct(impl, impl Reflect)]
pub struct Gloss {
    pub k: f32,
    pub tint: Vec3,
}

#[rt_impl]
impl Reflect for Matte {
    fn albedo(&self) -> f32 {
        self.a.clamp(0.0, 1.0)
    }
}

#[rt_impl]
impl Reflect for Gloss {
    const GAIN: f32 = 2.0;
    fn albedo(&self) -> f32 {
        self.k * 0.5 + self.tint.y
    }
    fn eval(&self, c: f32) -> f32 {
        c - self.albedo() * Self::GAIN
    }
}

#[rt_impl]
impl Gloss {
    pub fn new(k: f32) -> Gloss {
        Gloss { k, tint: Vec3::new(0.0, 0.25, 0.0) }
    }
}

/// Generic over the trait: one instance per model.
#[rt_function]
pub fn shade<R: Reflect>(r: R, c: f32) -> f32 {
    r.eval(c) + R::GAIN
}

/// Two models of possibly different types.
#[rt_function]
pub fn blend_two<A: Reflect, B: Reflect>(a: A, b: B, t: f32) -> f32 {
    a.albedo() * (1.0 - t) + b.albedo() * t
}

differential! {
    /// Trait methods by the receiver's type, defaults, generics over the trait.
    fn trait_dispatch {
        models(a: f32, c: f32) -> [f32; 6] over pairs(&spread(7, -0.5, 1.5), &spread(6, -2.0, 2.0)), tol CHAINED => {
            let m = Matte { a };
            let g = Gloss::new(a);
            [m.eval(c), g.eval(c), shade(m, c), shade(g, c), blend_two(m, g, 0.25), blend_two(g, g, 0.5) + Matte::GAIN + Gloss::GAIN]
        }
    }
}

/// An enum with an inherent block and an impl of the trait.
#[rt_enum(impl, impl Reflect)]
pub enum Finish {
    Chalk,
    Satin,
    Mirror,
}

#[rt_impl]
impl Finish {
    pub const COUNT: u32 = 3;

    /// The finish a number picks, cycling.
    pub fn from_index(i: u32) -> Finish {
        match i % Self::COUNT {
            0 => Finish::Chalk,
            1 => Finish::Satin,
            _ => Finish::Mirror,
        }
    }

    pub fn sharpness(&self) -> f32 {
        match self {
            Finish::Chalk => 0.0,
            Finish::Satin => 0.5,
            Finish::Mirror => 1.0,
        }
    }

    /// The next finish, in place.
    pub fn advance(&mut self) {
        *self = Finish::from_index(*self as u32 + 1);
    }
}

#[rt_impl]
impl Reflect for Finish {
    const GAIN: f32 = 0.5;
    fn albedo(&self) -> f32 {
        if *self == Finish::Mirror { 0.9 } else { 0.2 + self.sharpness() }
    }
}

differential! {
    /// An enum's methods and its trait impl, through a generic too.
    fn enum_trait_dispatch {
        enum_models(a: f32, c: f32) -> [f32; 6] over pairs(&spread(7, 0.0, 6.0), &spread(6, -2.0, 2.0)), tol CHAINED => {
            let mut f = Finish::from_index(a as u32);
            let before = f.eval(c);
            f.advance();
            let m = Matte { a: a * 0.1 };
            [before, f.eval(c), shade(f, c), blend_two(f, m, 0.5), f.sharpness() + Finish::GAIN, Finish::from_index(2).albedo()]
        }
    }
}
