//! Generic `#[rt_impl]` methods and associated functions, one WGSL
//! function per instance (`rtm_Bar__scaled__Vec3`): their arguments
//! inferred from the arguments' types, given by a turbofish or taken from
//! the type the result is wanted at; `&self`, `&mut self` and by path.

use super::*;
use core::ops::{Add, Mul};

/// A weight with generic operations.
#[rt_struct(impl)]
pub struct Bar {
    pub w: f32,
}

#[rt_impl]
impl Bar {
    /// Any value that scales by `f32`, scaled by the weight.
    pub fn scaled<T: Copy + Mul<f32, Output = T>>(&self, v: T) -> T {
        v * self.w
    }

    /// The weighted sum of an array of any length.
    pub fn weigh<const N: usize>(&self, a: [f32; N]) -> f32 {
        let mut s = 0.0;
        for i in 0..N {
            s += a[i] * self.w;
        }
        s
    }

    /// Adds a value of any additive type to a place, the weight grows.
    pub fn accumulate<T: Copy + Add<Output = T>>(&mut self, acc: &mut T, v: T) {
        *acc = *acc + v;
        self.w += 1.0;
    }

    /// A generic associated function: the default value of any type it
    /// is asked for.
    pub fn zero<T: Default>() -> T {
        T::default()
    }

    /// A generic method calling a generic method.
    pub fn twice<T: Copy + Mul<f32, Output = T>>(&self, v: T) -> T {
        self.scaled(self.scaled(v))
    }
}

/// A helper calling a generic method.
#[rt_function]
pub fn bar_tint(b: Bar, c: Vec3) -> Vec3 {
    b.scaled(c) + b.scaled::<Vec3>(Vec3::ONE)
}

differential! {
    /// Generic methods at several types each.
    fn generic_method_calls {
        /// Inferred, by turbofish, by path, by the wanted type, `&mut self`.
        methods_at_types(a: f32, b: f32) -> [f32; 8] over pairs(&spread(7, -3.0, 3.0), &spread(5, -1.0, 2.0)), tol CHAINED => {
            let bar = Bar { w: b };
            let s = bar.scaled(a);
            let v = bar.scaled::<Vec3>(Vec3::new(a, b, 1.0));
            let by_path = Bar::scaled(&bar, Vec2::new(a, 2.0));
            let mut m = Bar { w: a };
            let mut acc = 1.0;
            m.accumulate(&mut acc, b);
            let mut u = UVec2::new(1, 2);
            m.accumulate(&mut u, UVec2::new(3, 4));
            let z: f32 = Bar::zero();
            let t = bar_tint(bar, Vec3::splat(a));
            [s + z, v.x + v.y + v.z, by_path.x * by_path.y, acc + m.w + (u.x + u.y) as f32, bar.weigh([a, b, 1.0]), bar.weigh([a, b]), bar.twice(a) + bar.twice(Vec2::splat(b)).y, t.x + Bar::zero::<Vec3>().y]
        }
    }
}
