//! `#[rt_impl]` methods: `&self`, `&mut self` and `self` methods,
//! associated functions and constants, called from programs, helpers and
//! other methods, on locals, fields, temporaries and values from buffers.

use super::*;

/// A 2D disc with its geometry as methods.
#[rt_struct(impl)]
pub struct Disc {
    pub center: Vec2,
    pub radius: f32,
}

#[rt_impl]
impl Disc {
    pub const ORIGIN: Vec2 = Vec2::ZERO;
    pub const HALF: f32 = 0.5;
    /// An associated constant from another, through `Self`.
    pub const QUARTER: f32 = Self::HALF * Self::HALF;

    pub fn new(center: Vec2, radius: f32) -> Self {
        Self { center, radius }
    }

    pub fn at_origin(radius: f32) -> Disc {
        Disc::new(Self::ORIGIN, radius)
    }

    pub fn area(&self) -> f32 {
        3.14159265 * self.radius * self.radius
    }

    pub fn contains(&self, p: Vec2) -> bool {
        (p - self.center).length() <= self.radius
    }

    /// Signed distance from the rim.
    pub fn distance(&self, p: Vec2) -> f32 {
        (p - self.center).length() - self.radius
    }

    pub fn scale(&mut self, k: f32) {
        self.radius *= k;
        if self.radius > 100.0 {
            self.radius = 100.0;
        }
    }

    pub fn shifted(mut self, by: Vec2) -> Self {
        self.center += by;
        self
    }

    /// A method calling methods and an associated function.
    pub fn union_bound(&self, other: &Disc) -> Disc {
        let d = (other.center - self.center).length();
        let r = (d + self.radius + other.radius) * Self::HALF;
        let dir = if d > 0.0 { (other.center - self.center) / d } else { Vec2::ZERO };
        Disc::new(self.center + dir * (r - self.radius), r.max(self.radius).max(other.radius))
    }
}

/// A counter with integer state changed through `&mut self`.
#[rt_struct(impl)]
pub struct Tally {
    pub hits: u32,
    pub misses: u32,
}

#[rt_impl]
impl Tally {
    pub fn record(&mut self, hit: bool) {
        if hit {
            self.hits += 1;
        } else {
            self.misses += 1;
        }
    }

    pub fn total(&self) -> u32 {
        self.hits + self.misses
    }
}

/// A helper calling methods.
#[rt_function]
pub fn classify_points(d: &Disc, a: Vec2, b: Vec2) -> Tally {
    let mut t = Tally { hits: 0, misses: 0 };
    t.record(d.contains(a));
    t.record(d.contains(b));
    t.record(Disc::contains(d, a + b));
    t
}

/// Two discs in one struct: `&mut self` on a field.
#[rt_struct]
pub struct DiscPair {
    pub inner: Disc,
    pub outer: Disc,
}

differential! {
    /// Methods on a struct value.
    fn methods_on_structs {
        /// `&self` and associated functions and constants.
        disc_queries(x: f32, y: f32) -> [f32; 4] over pairs(&spread(7, -3.0, 3.0), &spread(5, -2.0, 2.0)), tol ulp_or_abs(8, 1e-5) => {
            let d = Disc::new(Vec2::new(x, y), 1.5);
            let o = Disc::at_origin(Disc::HALF + Disc::QUARTER);
            let inside = if o.contains(d.center) { 1.0 } else { 0.0 };
            [d.area(), o.distance(d.center), inside, Disc::area(&o)]
        }
        /// `&mut self` on a local, a field and a temporary; `self` by value.
        disc_changes(x: f32, k: f32) -> [f32; 4] over pairs(&spread(6, -2.0, 2.0), &[0.5, 1.0, 3.0, 200.0]), tol ulp_or_abs(8, 1e-5) => {
            let mut d = Disc::new(Vec2::new(x, 0.0), 1.0);
            d.scale(k);
            let mut pair = DiscPair { inner: d, outer: d.shifted(Vec2::new(0.0, 1.0)) };
            pair.outer.scale(2.0);
            let moved = Disc::new(Vec2::ONE, k).shifted(Vec2::X);
            let b = pair.inner.union_bound(&pair.outer);
            [pair.inner.radius, pair.outer.radius + pair.outer.center.y, moved.center.x, b.radius]
        }
        /// A helper calling methods; integer state through `&mut self`.
        tallies(x: f32, y: f32) -> [u32; 3] over pairs(&spread(5, -2.0, 2.0), &spread(5, -2.0, 2.0)) => {
            let d = Disc::new(Vec2::new(0.5, 0.0), 1.25);
            let t = classify_points(&d, Vec2::new(x, y), Vec2::new(y, x));
            [t.hits, t.misses, t.total()]
        }
    }
}
