//! Methods (`#[rt_impl]`): `&self`, `&mut self` and `self` methods,
//! associated functions and constants of a struct, a payload and an
//! attribute struct; `Self` in types, literals and paths; methods calling
//! methods, helpers and associated functions; a helper calling methods;
//! `&mut self` on a local, a field, a payload behind `&mut` and a
//! temporary; UFCS (`Ball::area(&b)`).
use rt_std::prelude::*;

/// A sphere, with its geometry as methods.
#[rt_struct(impl)]
pub struct Ball {
    pub center: Vec3,
    pub radius: f32,
}

#[rt_impl]
impl Ball {
    /// The unit ball's radius.
    pub const UNIT: f32 = 1.0;
    /// Twice `UNIT`, through `Self`.
    pub const DOUBLE: f32 = Self::UNIT * 2.0;

    pub fn new(center: Vec3, radius: f32) -> Self {
        Self { center, radius }
    }

    pub fn unit() -> Ball {
        Ball::new(Vec3::ZERO, Self::UNIT)
    }

    pub fn area(&self) -> f32 {
        4.0 * core::f32::consts::PI * self.radius * self.radius
    }

    /// A method calling a method.
    pub fn volume(&self) -> f32 {
        self.area() * self.radius / 3.0
    }

    pub fn contains(&self, p: Vec3) -> bool {
        (p - self.center).length_squared() <= self.radius * self.radius
    }

    pub fn grow(&mut self, by: f32) {
        self.radius += by;
        if self.radius > Self::DOUBLE * 4.0 {
            self.radius = Self::DOUBLE * 4.0;
        }
    }

    /// `self` by value (every declared type is `Copy`), with a `mut`
    /// binding.
    pub fn moved(mut self, by: Vec3) -> Self {
        self.center += by;
        self
    }

    /// A method calling a helper that does not name `Ball`.
    pub fn jittered(&self, state: &mut u32) -> Ball {
        let j = ball_rand(state) * 0.01;
        self.moved(Vec3::splat(j))
    }
}

/// A xorshift step (names no `Ball`, so a method may call it).
#[rt_function]
pub fn ball_rand(state: &mut u32) -> f32 {
    let mut x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    (x >> 8) as f32 / 16777216.0
}

/// A helper calling methods.
#[rt_function]
pub fn total_volume(a: &Ball, b: Ball) -> f32 {
    a.volume() + b.volume()
}

/// Two balls: `&mut self` on a field.
#[rt_struct]
pub struct BallPair {
    pub a: Ball,
    pub b: Ball,
}

#[rt_program(ray_generation)]
pub fn methods_balls(#[var] balls: Buffer<Ball>, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let mut b = balls[i];
    b.grow(0.5);
    let mut seed = i * 7 + 1;
    let j = b.jittered(&mut seed);
    let mut pair = BallPair { a: b, b: Ball::unit() };
    pair.b.grow(Ball::UNIT);
    let grown = Ball::new(Vec3::ONE, 0.25).moved(Vec3::X);
    let mut t = Ball::new(Vec3::ZERO, 1.0);
    t.grow(Ball::area(&grown));
    let inside = if pair.a.contains(j.center) { 1.0 } else { 0.0 };
    out[i] = Vec4::new(total_volume(&pair.a, pair.b), t.radius, inside, grown.center.x + Ball::DOUBLE);
}

/// A payload with methods.
#[rt_payload(impl)]
pub struct Glow {
    pub color: Vec3,
    pub bounces: u32,
}

#[rt_impl]
impl Glow {
    pub const MAX_BOUNCES: u32 = 4;

    pub fn add(&mut self, c: Vec3) {
        if self.bounces < Self::MAX_BOUNCES {
            self.color += c;
            self.bounces += 1;
        }
    }

    pub fn luminance(&self) -> f32 {
        self.color.dot(Vec3::new(0.2126, 0.7152, 0.0722))
    }
}

/// Attributes with a method.
#[rt_attributes(impl)]
pub struct BallHit {
    pub normal: Vec3,
    pub t: f32,
}

#[rt_impl]
impl BallHit {
    pub fn facing(&self, dir: Vec3) -> Vec3 {
        if self.normal.dot(dir) < 0.0 { self.normal } else { -self.normal }
    }
}

#[rt_program(closest_hit)]
pub fn methods_shade(prd: &mut Glow, attr: &BallHit) {
    let n = attr.facing(current_ray().direction);
    prd.add(n * 0.5 + 0.5);
    let l = prd.luminance();
    prd.add(Vec3::splat(l * attr.t));
}

/// Methods before and after a trace: the program keeps its resumable form.
#[rt_program(ray_generation)]
pub fn methods_trace(#[var] top: Object, #[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let mut prd = Glow { color: Vec3::ZERO, bounces: 0 };
    prd.add(Vec3::splat(0.1));
    let b = Ball::new(Vec3::ZERO, 2.0);
    rt_trace(top, Ray::new(b.center, Vec3::Z, 0, 1e-3, b.radius * 10.0), &mut prd);
    prd.add(Vec3::X);
    out[i] = prd.color.extend(prd.luminance());
}
