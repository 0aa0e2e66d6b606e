//! Generic structs (`#[rt_struct] struct Interval<T>`): one WGSL struct per
//! instance, named after its arguments (`rt_Interval__f32`,
//! `rt_Interval__Vec3`), its fields substituted; the methods of the
//! generic `#[rt_impl]` block one function per instance
//! (`rtm_Interval__width__f32`); a generic struct holding another; an
//! instance in a plain helper's signature, shared with the program.
use rt_std::prelude::*;

/// A range of any type with `-`.
#[rt_struct(impl)]
pub struct Interval<T> {
    pub lo: T,
    pub hi: T,
}

#[rt_impl]
impl<T: Copy + core::ops::Sub<Output = T>> Interval<T> {
    pub fn new(lo: T, hi: T) -> Self {
        Self { lo, hi }
    }

    pub fn width(&self) -> T {
        self.hi - self.lo
    }
}

/// An interval with a label.
#[rt_struct]
pub struct Labelled<T> {
    pub range: Interval<T>,
    pub label: u32,
}

/// A plain helper taking an instance the program uses too.
#[rt_function]
pub fn clamp_into(x: f32, r: Interval<f32>) -> f32 {
    x.clamp(r.lo, r.hi)
}

#[rt_program(ray_generation)]
pub fn generic_intervals(#[var] mut out: RwBuffer<Vec4>) {
    let i = launch_index().x;
    let x = i as f32;
    let unit = Interval { lo: 0.0, hi: 1.0 };
    let boxed: Interval<Vec3> = Interval::new(Vec3::ZERO, Vec3::splat(x));
    let tagged = Labelled { range: Interval::<f32> { lo: -x, hi: x }, label: i };
    out[i] = Vec4::new(clamp_into(x, unit), boxed.width().y, tagged.range.width(), tagged.label as f32);
}
