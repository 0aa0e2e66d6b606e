//! The methods whose Rust (std or glam) versions panic where the GPU
//! answers, called through [`Gpu`].
//!
//! The macro rewrites `x.dot(y)` into `Gpu(x).dot(y)` (and the path form
//! `IVec3::dot(a, b)` into `Gpu::<IVec3>(a).dot(b)`) for the names in
//! `rt-compiler`'s `cpu_semantics.rs`, without knowing `x`'s type. Rust's
//! method lookup then decides: `Gpu<T>` has an inherent method of that
//! name only for the types whose meaning differs (the integers and their
//! vectors, whose arithmetic wraps on the GPU, and the clamps, which do not
//! panic there), so those are called; for any other type (a float vector,
//! a matrix, a user's `#[rt_struct]` with a method of the same name) the
//! lookup goes on through `Deref` to the value's own method.
//!
//! Sums and products of integers wrap, as the GPU's do, and raise
//! `EXCEPTION_INTEGER_OVERFLOW` where integer exceptions are on, as the
//! operators do.

use super::{Int, RtAbs, RtClamp, RtDivide, overflowed, trap};
use glam::{BVec2, BVec3, BVec4, IVec2, IVec3, IVec4, Mat2, Mat3, Mat4, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4};

/// A value whose method is called with the GPU's meaning (see the module).
#[doc(hidden)]
#[derive(Clone, Copy)]
pub struct Gpu<T>(pub T);

impl<T> core::ops::Deref for Gpu<T> {
    type Target = T;
    #[inline(always)]
    fn deref(&self) -> &T {
        &self.0
    }
}

/// A place whose in-place method (`m.set_row(i, v)`, `m.col_mut(i)`,
/// `mask.set(i, b)`) is
/// called with the GPU's meaning: the index clamped to the last row or
/// component, as indexing is, where glam panics. The macro writes
/// `GpuMut(&mut m).set_row(i, v)` (`&mut *m` for a `&mut` parameter `m`);
/// any other type reaches its own method through `DerefMut`.
#[doc(hidden)]
pub struct GpuMut<'a, T>(pub &'a mut T);

impl<T> core::ops::Deref for GpuMut<'_, T> {
    type Target = T;
    #[inline(always)]
    fn deref(&self) -> &T {
        self.0
    }
}

impl<T> core::ops::DerefMut for GpuMut<'_, T> {
    #[inline(always)]
    fn deref_mut(&mut self) -> &mut T {
        self.0
    }
}

macro_rules! set_row {
    ($($m:ty: $v:ty, $n:literal);*) => {$(
        impl<'a> GpuMut<'a, $m> {
            #[inline(always)]
            pub fn set_row(self, index: usize, value: $v) {
                self.0.set_row(index.min($n - 1), value)
            }
            #[inline(always)]
            pub fn col_mut(self, index: usize) -> &'a mut $v {
                self.0.col_mut(index.min($n - 1))
            }
        }
    )*};
}
set_row!(Mat2: Vec2, 2; Mat3: Vec3, 3; Mat4: Vec4, 4);

macro_rules! bool_vector {
    ($($b:ty, $n:literal);*) => {$(
        impl GpuMut<'_, $b> {
            #[inline(always)]
            pub fn set(self, index: usize, value: bool) {
                self.0.set(index.min($n - 1), value)
            }
        }
        impl Gpu<$b> {
            #[inline(always)]
            pub fn test(self, index: usize) -> bool {
                self.0.test(index.min($n - 1))
            }
        }
    )*};
}
bool_vector!(BVec2, 2; BVec3, 3; BVec4, 4);

/// glam's minors, the column and row left out clamped to the last (glam
/// panics past it): the macro writes `Gpu::<Mat2>::from_mat3_minor(..)`
/// for `Mat2::from_mat3_minor(..)`.
impl Gpu<Mat2> {
    #[inline(always)]
    pub fn from_mat3_minor(m: Mat3, i: usize, j: usize) -> Mat2 {
        Mat2::from_mat3_minor(m, i.min(2), j.min(2))
    }
}

impl Gpu<Mat3> {
    #[inline(always)]
    pub fn from_mat4_minor(m: Mat4, i: usize, j: usize) -> Mat3 {
        Mat3::from_mat4_minor(m, i.min(3), j.min(3))
    }
}

/// The dividing methods and `clamp`, for every integer type and vector.
macro_rules! dividing_and_clamp {
    ($($t:ty),*) => {$(
        impl Gpu<$t> {
            #[track_caller]
            #[inline(always)]
            pub fn div_euclid(self, b: $t) -> $t {
                self.0.rt_div_euclid(b)
            }
            #[track_caller]
            #[inline(always)]
            pub fn rem_euclid(self, b: $t) -> $t {
                self.0.rt_rem_euclid(b)
            }
            #[track_caller]
            #[inline(always)]
            pub fn wrapping_div(self, b: $t) -> $t {
                self.0.rt_wrapping_div(b)
            }
            #[track_caller]
            #[inline(always)]
            pub fn saturating_div(self, b: $t) -> $t {
                self.0.rt_saturating_div(b)
            }
            #[track_caller]
            #[inline(always)]
            pub fn clamp(self, lo: $t, hi: $t) -> $t {
                self.0.rt_clamp(lo, hi)
            }
        }
    )*};
}
dividing_and_clamp!(i32, u32, IVec2, IVec3, IVec4, UVec2, UVec3, UVec4);

/// Float clamps: `min(max(x, lo), hi)` where Rust's `f32::clamp` panics
/// (`lo > hi`, a NaN bound).
macro_rules! float_clamp {
    ($($t:ty),*) => {$(
        impl Gpu<$t> {
            #[track_caller]
            #[inline(always)]
            pub fn clamp(self, lo: $t, hi: $t) -> $t {
                self.0.rt_clamp(lo, hi)
            }
        }
    )*};
}
float_clamp!(f32, Vec2, Vec3, Vec4);

/// A zero divisor of std's integer methods: raises where integer
/// exceptions are on, and reads as one.
#[track_caller]
#[inline(always)]
fn divisor<T: PartialEq + From<u8>>(b: T) -> T {
    if b == T::from(0) {
        trap(crate::EXCEPTION_INTEGER_DIVIDE_BY_ZERO);
        T::from(1)
    } else {
        b
    }
}

/// std's integer methods that panic (`rt-compiler`'s
/// `lower/builtins/std_scalars.rs` gives their GPU meaning): `pow` wraps,
/// a zero divisor reads as one, a logarithm or root with no answer is 0.
macro_rules! std_int {
    ($($t:ty),*) => {$(
        impl Gpu<$t> {
            #[track_caller]
            #[inline(always)]
            pub fn pow(self, exp: u32) -> $t {
                overflowed(self.0.overflowing_pow(exp))
            }
            #[track_caller]
            #[inline(always)]
            pub fn wrapping_rem(self, b: $t) -> $t {
                self.0.wrapping_rem(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn wrapping_div_euclid(self, b: $t) -> $t {
                self.0.wrapping_div_euclid(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn wrapping_rem_euclid(self, b: $t) -> $t {
                self.0.wrapping_rem_euclid(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn overflowing_div(self, b: $t) -> ($t, bool) {
                self.0.overflowing_div(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn overflowing_rem(self, b: $t) -> ($t, bool) {
                self.0.overflowing_rem(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn overflowing_div_euclid(self, b: $t) -> ($t, bool) {
                self.0.overflowing_div_euclid(divisor(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn overflowing_rem_euclid(self, b: $t) -> ($t, bool) {
                self.0.overflowing_rem_euclid(divisor(b))
            }
            #[inline(always)]
            pub fn ilog2(self) -> u32 {
                self.0.checked_ilog2().unwrap_or(0)
            }
            #[inline(always)]
            pub fn ilog10(self) -> u32 {
                self.0.checked_ilog10().unwrap_or(0)
            }
            #[inline(always)]
            pub fn ilog(self, base: $t) -> u32 {
                if base < 2 { 0 } else { self.0.checked_ilog(base).unwrap_or(0) }
            }
        }
    )*};
}
std_int!(i32, u32);

impl Gpu<i32> {
    #[inline(always)]
    pub fn isqrt(self) -> i32 {
        self.0.checked_isqrt().unwrap_or(0)
    }
}

impl Gpu<u32> {
    #[track_caller]
    #[inline(always)]
    pub fn div_ceil(self, b: u32) -> u32 {
        self.0.div_ceil(divisor(b))
    }

    #[track_caller]
    #[inline(always)]
    pub fn next_multiple_of(self, b: u32) -> u32 {
        let b = divisor(b);
        match self.0 % b {
            0 => self.0,
            r => overflowed(self.0.overflowing_add(b - r)),
        }
    }

    #[track_caller]
    #[inline(always)]
    pub fn next_power_of_two(self) -> u32 {
        match self.0.checked_next_power_of_two() {
            Some(p) => p,
            None => {
                trap(crate::EXCEPTION_INTEGER_OVERFLOW);
                0
            }
        }
    }
}

/// `abs` of `i32::MIN` is `i32::MIN`.
macro_rules! signed_abs {
    ($($t:ty),*) => {$(
        impl Gpu<$t> {
            #[track_caller]
            #[inline(always)]
            pub fn abs(self) -> $t {
                self.0.rt_abs()
            }
        }
    )*};
}
signed_abs!(i32, IVec2, IVec3, IVec4);

/// Wrapping `a + b` and `a * b` of integer components (`Int`'s, which
/// raise where integer exceptions are on).
#[track_caller]
#[inline(always)]
fn sum<S: Int>(parts: &[S]) -> S {
    let mut s = parts[0];
    for &p in &parts[1..] {
        s = s.i_add(p);
    }
    s
}

#[track_caller]
#[inline(always)]
fn product<S: Int>(parts: &[S]) -> S {
    let mut s = parts[0];
    for &p in &parts[1..] {
        s = s.i_mul(p);
    }
    s
}

#[track_caller]
#[inline(always)]
fn products<S: Int, const N: usize>(a: [S; N], b: [S; N]) -> [S; N] {
    let mut out = a;
    for i in 0..N {
        out[i] = a[i].i_mul(b[i]);
    }
    out
}

/// `|a - b|` of one component, as `u32` (glam's `abs_diff`: never
/// overflows).
trait AbsDiff: Copy {
    fn abs_diff_u32(self, b: Self) -> u32;
}
impl AbsDiff for i32 {
    #[inline(always)]
    fn abs_diff_u32(self, b: i32) -> u32 {
        self.abs_diff(b)
    }
}
impl AbsDiff for u32 {
    #[inline(always)]
    fn abs_diff_u32(self, b: u32) -> u32 {
        self.abs_diff(b)
    }
}

/// The sums and products of integer vectors: `dot`, `dot_into_vec`,
/// `element_sum`, `element_product`, `length_squared`, `manhattan_distance`.
macro_rules! int_vector_sums {
    ($($v:ident: $s:ty),*) => {$(
        impl Gpu<$v> {
            #[track_caller]
            #[inline(always)]
            pub fn dot(self, b: $v) -> $s {
                sum(&products(self.0.to_array(), b.to_array()))
            }
            #[track_caller]
            #[inline(always)]
            pub fn dot_into_vec(self, b: $v) -> $v {
                <$v>::splat(self.dot(b))
            }
            #[track_caller]
            #[inline(always)]
            pub fn element_sum(self) -> $s {
                sum(&self.0.to_array())
            }
            #[track_caller]
            #[inline(always)]
            pub fn element_product(self) -> $s {
                product(&self.0.to_array())
            }
            #[track_caller]
            #[inline(always)]
            pub fn length_squared(self) -> $s {
                self.dot(self.0)
            }
            #[track_caller]
            #[inline(always)]
            pub fn manhattan_distance(self, b: $v) -> u32 {
                let (a, b) = (self.0.to_array(), b.to_array());
                let mut d = a.map(|_| 0u32);
                for i in 0..d.len() {
                    d[i] = a[i].abs_diff_u32(b[i]);
                }
                sum(&d)
            }
        }
    )*};
}
int_vector_sums!(IVec2: i32, IVec3: i32, IVec4: i32, UVec2: u32, UVec3: u32, UVec4: u32);

/// `distance_squared` (glam has it for the signed vectors only).
macro_rules! signed_distance {
    ($($v:ident: $s:ty),*) => {$(
        impl Gpu<$v> {
            #[track_caller]
            #[inline(always)]
            pub fn distance_squared(self, b: $v) -> $s {
                let d = super::sub(self.0, b);
                Gpu(d).dot(d)
            }
        }
    )*};
}
signed_distance!(IVec2: i32, IVec3: i32, IVec4: i32);

/// `cross` of three-component integer vectors.
macro_rules! int_cross {
    ($($v:ident),*) => {$(
        impl Gpu<$v> {
            #[track_caller]
            #[inline(always)]
            pub fn cross(self, b: $v) -> $v {
                let a = self.0;
                <$v>::new(
                    a.y.i_mul(b.z).i_sub(b.y.i_mul(a.z)),
                    a.z.i_mul(b.x).i_sub(b.z.i_mul(a.x)),
                    a.x.i_mul(b.y).i_sub(b.x.i_mul(a.y)),
                )
            }
        }
    )*};
}
int_cross!(IVec3, UVec3);

impl Gpu<IVec2> {
    #[track_caller]
    #[inline(always)]
    pub fn perp_dot(self, b: IVec2) -> i32 {
        let a = self.0;
        a.x.i_mul(b.y).i_sub(a.y.i_mul(b.x))
    }

    #[track_caller]
    #[inline(always)]
    pub fn rotate(self, b: IVec2) -> IVec2 {
        let a = self.0;
        IVec2::new(a.x.i_mul(b.x).i_sub(a.y.i_mul(b.y)), a.y.i_mul(b.x).i_add(a.x.i_mul(b.y)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integer_sums_wrap_where_glam_would_panic() {
        let big = IVec3::splat(i32::MAX);
        assert_eq!(Gpu(big).element_sum(), i32::MAX.wrapping_mul(3));
        assert_eq!(Gpu(big).element_product(), i32::MAX.wrapping_mul(i32::MAX).wrapping_mul(i32::MAX));
        assert_eq!(Gpu(big).dot(IVec3::splat(2)), i32::MAX.wrapping_mul(6));
        assert_eq!(Gpu(big).length_squared(), 3);
        assert_eq!(Gpu(big).distance_squared(IVec3::splat(i32::MIN)), 3);
        assert_eq!(Gpu(big).dot_into_vec(IVec3::ONE), IVec3::splat(i32::MAX.wrapping_mul(3)));
        assert_eq!(
            Gpu(IVec2::new(i32::MAX, i32::MIN)).manhattan_distance(IVec2::new(i32::MIN, i32::MAX)),
            u32::MAX - 1
        );
        assert_eq!(Gpu(UVec3::ZERO).cross(UVec3::new(1, 2, 3)), UVec3::ZERO);
        assert_eq!(Gpu(UVec3::X).cross(UVec3::Y), UVec3::Z);
        assert_eq!(Gpu(UVec3::Y).cross(UVec3::X), UVec3::new(0, 0, u32::MAX));
        assert_eq!(Gpu(IVec2::new(i32::MAX, 2)).perp_dot(IVec2::new(3, 1)), i32::MAX.wrapping_sub(6));
        assert_eq!(Gpu(IVec2::new(i32::MAX, 1)).rotate(IVec2::new(2, 0)), IVec2::new(-2, 2));
        assert_eq!(Gpu(i32::MIN).abs(), i32::MIN);
        assert_eq!(Gpu(IVec2::new(i32::MIN, -3)).abs(), IVec2::new(i32::MIN, 3));
        assert_eq!(Gpu(5u32).clamp(7, 2), 2);
        assert_eq!(Gpu(1.5f32).clamp(2.0, 1.0), 1.0);
        assert_eq!(Gpu(7i32).div_euclid(0), 7);
        assert_eq!(Gpu(3i32).pow(31), 3i32.wrapping_pow(31));
        assert_eq!(
            (Gpu(7u32).wrapping_rem(0), Gpu(-7i32).wrapping_rem_euclid(0), Gpu(i32::MIN).wrapping_div_euclid(-1)),
            (0, 0, i32::MIN)
        );
        assert_eq!(
            (Gpu(0u32).ilog2(), Gpu(-5i32).ilog10(), Gpu(100u32).ilog(1), Gpu(100u32).ilog(10), Gpu(-4i32).isqrt()),
            (0, 0, 0, 2, 0)
        );
        assert_eq!(
            (
                Gpu(7u32).div_ceil(0),
                Gpu(7u32).div_ceil(2),
                Gpu(7u32).next_multiple_of(0),
                Gpu(u32::MAX).next_multiple_of(2)
            ),
            (7, 4, 7, 0)
        );
        assert_eq!(
            (Gpu(0u32).next_power_of_two(), Gpu(5u32).next_power_of_two(), Gpu(u32::MAX).next_power_of_two()),
            (1, 8, 0)
        );
    }

    #[test]
    fn in_place_methods_clamp_the_index() {
        let mut m = Mat3::IDENTITY;
        GpuMut(&mut m).set_row(7, Vec3::new(4.0, 5.0, 6.0));
        assert_eq!(m.row(2), Vec3::new(4.0, 5.0, 6.0));
        *GpuMut(&mut m).col_mut(5) = Vec3::ONE;
        assert_eq!(m.z_axis, Vec3::ONE);
        let mut b = BVec3::FALSE;
        GpuMut(&mut b).set(9, true);
        assert_eq!(b, BVec3::new(false, false, true));
        assert!(Gpu(b).test(3));
        assert!(!Gpu(b).test(0));
        // Another type's own method, through `DerefMut`.
        struct Mine(u32);
        impl Mine {
            fn set(&mut self, i: usize, v: bool) {
                self.0 = i as u32 + v as u32;
            }
        }
        let mut mine = Mine(0);
        GpuMut(&mut mine).set(4, true);
        assert_eq!(mine.0, 5);
    }

    #[test]
    fn other_types_reach_their_own_methods() {
        // Float vectors and matrices have no inherent `Gpu` method of these
        // names: the lookup goes on to glam's.
        assert_eq!(Gpu(Vec3::new(1.0, 2.0, 3.0)).dot(Vec3::ONE), 6.0);
        assert_eq!(Gpu(Vec3::X).cross(Vec3::Y), Vec3::Z);
        assert_eq!(Gpu(glam::Mat2::from_cols_array(&[-1.0, 2.0, -3.0, 4.0])).abs().x_axis, Vec2::new(1.0, 2.0));
        assert_eq!(Gpu(-2.5f32).abs(), 2.5);
        assert_eq!(Gpu(Vec4::ONE).element_sum(), 4.0);
        struct Mine(u32);
        impl Mine {
            fn dot(&self, k: u32) -> u32 {
                self.0 * k
            }
        }
        assert_eq!(Gpu(Mine(3)).dot(4), 12);
    }
}
