//! One integer semantics on every backend: what the GPU does, in debug and
//! release builds alike.
//!
//! Rust panics on integer overflow in debug builds and on division by zero
//! and out-of-range indices in every build; WGSL (as naga emits it) defines
//! all of them. A ray program must give the same answer wherever it runs and
//! must not take a launch down, so the CPU copy of every `#[rt_program]` and
//! `#[rt_function]` is rewritten by the macro to call the functions of this
//! module instead of the operators, and they do what the megakernel does:
//!
//! | expression | result |
//! | --- | --- |
//! | `a + b`, `a - b`, `a * b`, `-a` on `u32`, `i32`, `usize` and their vectors | wraps (two's complement, 32 bits; `usize` is 32 bits wide in WGSL) |
//! | `a / 0` | `a` |
//! | `a % 0` | `0` |
//! | `i32::MIN / -1` | `i32::MIN` |
//! | `i32::MIN % -1` | `0` |
//! | `a.div_euclid(0)`, `a.wrapping_div(0)`, `a.saturating_div(0)`, `a.div_ceil(0)`, `a.next_multiple_of(0)`; `a.rem_euclid(0)`, `a.wrapping_rem(0)` | `a`; `0` (the divisor read as one, [`Gpu`]'s methods) |
//! | `a.pow(n)` past the range; `dot`, `element_sum`, `element_product`, `cross`, `length_squared`, `manhattan_distance`... of integer vectors | wraps, as `*` and `+` do |
//! | `a.ilog2()`, `a.ilog10()`, `a.ilog(b)`, `a.isqrt()` where std has no answer (`a <= 0`, `b < 2`) | `0` |
//! | `a.next_power_of_two()` past `2^31` | `0` |
//! | `m.set_row(i, ..)`, `m.col_mut(i)`, `mask.set(i, ..)`, `mask.test(i)`, `Mat3::from_mat4_minor(m, i, j)` past the end | the last row, column or component ([`GpuMut`], [`Gpu`]) |
//! | `i32::MIN.div_euclid(-1)`, `.wrapping_div(-1)`; `.saturating_div(-1)` | `i32::MIN`; `i32::MAX` |
//! | `a << n`, `a >> n` with `n >= 32` | shifts by `n % 32` (`>>` on `i32` is arithmetic) |
//! | `x as i32`, `x as u32` for `f32` NaN | `0` |
//! | `x as i32`, `x as u32` for `f32` out of range | the nearest representable value (saturating) |
//! | `arr[i]`, `v[i]` with `i` past the end of a local array or vector | the last element (naga's `Restrict` bounds-check policy) |
//! | `buf[i]` with `i` past the end of a buffer | raises `EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS` ([`crate::buffer`]) |
//!
//! Floating-point operators keep Rust's (IEEE) meaning. `abs` of
//! `i32::MIN` is `i32::MIN`, as on the GPU (`wrapping_abs`).
//!
//! The functions are `#[doc(hidden)]` plumbing for the macro: programs write
//! the operators.

mod division;
mod indexing;
mod methods;
mod panics;
mod references;
use division::RtDivide;
pub use indexing::{RtIndex, RtIndexMut};
pub use methods::{Gpu, GpuMut};
pub use panics::{RtUnwrap, debug_assert_failed, expect, unwrap};

use glam::{IVec2, IVec3, IVec4, Mat2, Mat3, Mat4, Quat, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4};

/// Types whose operators keep Rust's meaning: floats, float vectors and
/// matrices, quaternions.
#[doc(hidden)]
pub trait Plain {}
impl Plain for f32 {}
impl Plain for Vec2 {}
impl Plain for Vec3 {}
impl Plain for Vec4 {}
impl Plain for Mat2 {}
impl Plain for Mat3 {}
impl Plain for Mat4 {}
impl Plain for Quat {}
impl Plain for bool {}

/// Whether integer exceptions are on for this thread's launch (the CPU
/// backend sets it around its work: [`checking_integers`]).
mod checking {
    use core::cell::Cell;
    thread_local! {
        pub static ON: Cell<bool> = const { Cell::new(false) };
    }
}

/// Runs `f` with integer exceptions `on` (or off) on this thread: an
/// overflow raises [`EXCEPTION_INTEGER_OVERFLOW`](crate::EXCEPTION_INTEGER_OVERFLOW),
/// a division by zero [`EXCEPTION_INTEGER_DIVIDE_BY_ZERO`](crate::EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
/// with the operator's place; the value is the wrapped one either way.
#[doc(hidden)]
pub fn checking_integers<R>(on: bool, f: impl FnOnce() -> R) -> R {
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            checking::ON.with(|c| c.set(self.0));
        }
    }
    let _restore = Restore(checking::ON.with(|c| c.replace(on)));
    f()
}

/// Raises `code` at the caller's operator when integer exceptions are on.
#[track_caller]
#[inline]
fn trap(code: u32) {
    if checking::ON.with(|c| c.get()) {
        crate::cpu::raise_here(code);
    }
}

#[track_caller]
#[inline(always)]
fn overflowed<T>((v, o): (T, bool)) -> T {
    if o {
        trap(crate::EXCEPTION_INTEGER_OVERFLOW);
    }
    v
}

/// Integer scalars with the GPU's meaning of each operator.
trait Int: Copy {
    fn i_add(self, b: Self) -> Self;
    fn i_sub(self, b: Self) -> Self;
    fn i_mul(self, b: Self) -> Self;
    fn i_div(self, b: Self) -> Self;
    fn i_rem(self, b: Self) -> Self;
    fn i_shl(self, n: u32) -> Self;
    fn i_shr(self, n: u32) -> Self;
}

macro_rules! int_impl {
    ($t:ty) => {
        impl Int for $t {
            #[track_caller]
            #[inline(always)]
            fn i_add(self, b: $t) -> $t {
                overflowed(self.overflowing_add(b))
            }
            #[track_caller]
            #[inline(always)]
            fn i_sub(self, b: $t) -> $t {
                overflowed(self.overflowing_sub(b))
            }
            #[track_caller]
            #[inline(always)]
            fn i_mul(self, b: $t) -> $t {
                overflowed(self.overflowing_mul(b))
            }
            #[track_caller]
            #[inline(always)]
            fn i_div(self, b: $t) -> $t {
                if b == 0 {
                    trap(crate::EXCEPTION_INTEGER_DIVIDE_BY_ZERO);
                    self
                } else {
                    overflowed(self.overflowing_div(b))
                }
            }
            #[track_caller]
            #[inline(always)]
            fn i_rem(self, b: $t) -> $t {
                if b == 0 {
                    trap(crate::EXCEPTION_INTEGER_DIVIDE_BY_ZERO);
                    0
                } else {
                    overflowed(self.overflowing_rem(b))
                }
            }
            #[track_caller]
            #[inline(always)]
            fn i_shl(self, n: u32) -> $t {
                overflowed(self.overflowing_shl(n))
            }
            #[track_caller]
            #[inline(always)]
            fn i_shr(self, n: u32) -> $t {
                overflowed(self.overflowing_shr(n))
            }
        }
    };
}
int_impl!(u32);
int_impl!(i32);

/// `usize` is `u32` in WGSL: it wraps at 32 bits.
impl Int for usize {
    #[track_caller]
    #[inline(always)]
    fn i_add(self, b: usize) -> usize {
        (self as u32).i_add(b as u32) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_sub(self, b: usize) -> usize {
        (self as u32).i_sub(b as u32) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_mul(self, b: usize) -> usize {
        (self as u32).i_mul(b as u32) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_div(self, b: usize) -> usize {
        (self as u32).i_div(b as u32) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_rem(self, b: usize) -> usize {
        (self as u32).i_rem(b as u32) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_shl(self, n: u32) -> usize {
        (self as u32).i_shl(n) as usize
    }
    #[track_caller]
    #[inline(always)]
    fn i_shr(self, n: u32) -> usize {
        (self as u32).i_shr(n) as usize
    }
}

macro_rules! binary_trait {
    ($trait:ident, $method:ident, $op:ident, $message:literal, $label:literal) => {
        #[doc(hidden)]
        #[diagnostic::on_unimplemented(message = $message, label = $label)]
        pub trait $trait<R> {
            type Output;
            fn $method(self, r: R) -> Self::Output;
        }
        #[diagnostic::do_not_recommend]
        impl<A: Plain + core::ops::$op<B>, B> $trait<B> for A {
            type Output = <A as core::ops::$op<B>>::Output;
            #[track_caller]
            #[inline(always)]
            fn $method(self, r: B) -> Self::Output {
                core::ops::$op::$method(self, r)
            }
        }
    };
}

binary_trait!(RtAdd, add, Add, "cannot add `{R}` to `{Self}`", "no implementation for `{Self} + {R}`");
binary_trait!(RtSub, sub, Sub, "cannot subtract `{R}` from `{Self}`", "no implementation for `{Self} - {R}`");
binary_trait!(RtMul, mul, Mul, "cannot multiply `{Self}` by `{R}`", "no implementation for `{Self} * {R}`");
binary_trait!(RtDiv, div, Div, "cannot divide `{Self}` by `{R}`", "no implementation for `{Self} / {R}`");
binary_trait!(
    RtRem,
    rem,
    Rem,
    "cannot calculate the remainder of `{Self}` divided by `{R}`",
    "no implementation for `{Self} % {R}`"
);

/// A shift: the amount is any integer scalar (or a vector of them for a
/// vector), taken modulo 32 as WGSL does.
#[doc(hidden)]
#[diagnostic::on_unimplemented(message = "cannot shift `{Self}` by `{R}`")]
pub trait RtShift<R> {
    fn shl(self, r: R) -> Self;
    fn shr(self, r: R) -> Self;
}

/// Negation: wraps on integers.
#[doc(hidden)]
#[diagnostic::on_unimplemented(message = "cannot apply unary `-` to `{Self}`")]
pub trait RtNeg {
    type Output;
    fn neg(self) -> Self::Output;
}

impl<A: Plain + core::ops::Neg> RtNeg for A {
    type Output = A::Output;
    #[track_caller]
    #[inline(always)]
    fn neg(self) -> A::Output {
        -self
    }
}

macro_rules! int_scalar {
    ($t:ty) => {
        impl RtAdd<$t> for $t {
            type Output = $t;
            #[track_caller]
            #[inline(always)]
            fn add(self, r: $t) -> $t {
                Int::i_add(self, r)
            }
        }
        impl RtSub<$t> for $t {
            type Output = $t;
            #[track_caller]
            #[inline(always)]
            fn sub(self, r: $t) -> $t {
                Int::i_sub(self, r)
            }
        }
        impl RtMul<$t> for $t {
            type Output = $t;
            #[track_caller]
            #[inline(always)]
            fn mul(self, r: $t) -> $t {
                Int::i_mul(self, r)
            }
        }
        impl RtDiv<$t> for $t {
            type Output = $t;
            #[track_caller]
            #[inline(always)]
            fn div(self, r: $t) -> $t {
                Int::i_div(self, r)
            }
        }
        impl RtRem<$t> for $t {
            type Output = $t;
            #[track_caller]
            #[inline(always)]
            fn rem(self, r: $t) -> $t {
                Int::i_rem(self, r)
            }
        }
        impl RtShift<u32> for $t {
            #[track_caller]
            #[inline(always)]
            fn shl(self, n: u32) -> $t {
                Int::i_shl(self, n)
            }
            #[track_caller]
            #[inline(always)]
            fn shr(self, n: u32) -> $t {
                Int::i_shr(self, n)
            }
        }
        impl RtShift<i32> for $t {
            #[track_caller]
            #[inline(always)]
            fn shl(self, n: i32) -> $t {
                Int::i_shl(self, n as u32)
            }
            #[track_caller]
            #[inline(always)]
            fn shr(self, n: i32) -> $t {
                Int::i_shr(self, n as u32)
            }
        }
        impl RtShift<usize> for $t {
            #[track_caller]
            #[inline(always)]
            fn shl(self, n: usize) -> $t {
                Int::i_shl(self, n as u32)
            }
            #[track_caller]
            #[inline(always)]
            fn shr(self, n: usize) -> $t {
                Int::i_shr(self, n as u32)
            }
        }
    };
}

int_scalar!(u32);
int_scalar!(i32);
int_scalar!(usize);

impl RtNeg for i32 {
    type Output = i32;
    #[track_caller]
    #[inline(always)]
    fn neg(self) -> i32 {
        overflowed(self.overflowing_neg())
    }
}

impl RtNeg for IVec2 {
    type Output = IVec2;
    #[track_caller]
    #[inline(always)]
    fn neg(self) -> IVec2 {
        0i32.sub(self)
    }
}
impl RtNeg for IVec3 {
    type Output = IVec3;
    #[track_caller]
    #[inline(always)]
    fn neg(self) -> IVec3 {
        0i32.sub(self)
    }
}
impl RtNeg for IVec4 {
    type Output = IVec4;
    #[track_caller]
    #[inline(always)]
    fn neg(self) -> IVec4 {
        0i32.sub(self)
    }
}

/// Integer vectors: each operator component-wise with the scalar's meaning,
/// vector with vector, vector with scalar and scalar with vector.
macro_rules! int_vector {
    ($v:ty, $s:ty, $uv:ty, $iv:ty) => {
        int_vector!(@op $v, $s, RtAdd, add, i_add);
        int_vector!(@op $v, $s, RtSub, sub, i_sub);
        int_vector!(@op $v, $s, RtMul, mul, i_mul);
        int_vector!(@op $v, $s, RtDiv, div, i_div);
        int_vector!(@op $v, $s, RtRem, rem, i_rem);
        int_vector!(@shift $v, u32);
        int_vector!(@shift $v, i32);
        int_vector!(@shifts $v, $uv, $iv);
    };
    (@shift $v:ty, $n:ty) => {
        impl RtShift<$n> for $v {
            #[track_caller]
    #[inline(always)]
            fn shl(self, n: $n) -> $v {
                let mut a = self.to_array();
                for x in a.iter_mut() {
                    *x = Int::i_shl(*x, n as u32);
                }
                <$v>::from_array(a)
            }
            #[track_caller]
    #[inline(always)]
            fn shr(self, n: $n) -> $v {
                let mut a = self.to_array();
                for x in a.iter_mut() {
                    *x = Int::i_shr(*x, n as u32);
                }
                <$v>::from_array(a)
            }
        }
    };
    (@shifts $v:ty, $($nv:ty),*) => {$(
        impl RtShift<$nv> for $v {
            #[track_caller]
    #[inline(always)]
            fn shl(self, n: $nv) -> $v {
                let (mut a, n) = (self.to_array(), n.to_array());
                for i in 0..a.len() {
                    a[i] = Int::i_shl(a[i], n[i] as u32);
                }
                <$v>::from_array(a)
            }
            #[track_caller]
    #[inline(always)]
            fn shr(self, n: $nv) -> $v {
                let (mut a, n) = (self.to_array(), n.to_array());
                for i in 0..a.len() {
                    a[i] = Int::i_shr(a[i], n[i] as u32);
                }
                <$v>::from_array(a)
            }
        }
    )*};
    (@op $v:ty, $s:ty, $trait:ident, $method:ident, $int:ident) => {
        impl $trait<$v> for $v {
            type Output = $v;
            #[track_caller]
    #[inline(always)]
            fn $method(self, r: $v) -> $v {
                let (mut a, r) = (self.to_array(), r.to_array());
                for i in 0..a.len() {
                    a[i] = Int::$int(a[i], r[i]);
                }
                <$v>::from_array(a)
            }
        }
        impl $trait<$s> for $v {
            type Output = $v;
            #[track_caller]
    #[inline(always)]
            fn $method(self, r: $s) -> $v {
                let mut a = self.to_array();
                for x in a.iter_mut() {
                    *x = Int::$int(*x, r);
                }
                <$v>::from_array(a)
            }
        }
        impl $trait<$v> for $s {
            type Output = $v;
            #[track_caller]
    #[inline(always)]
            fn $method(self, r: $v) -> $v {
                let mut a = r.to_array();
                for x in a.iter_mut() {
                    *x = Int::$int(self, *x);
                }
                <$v>::from_array(a)
            }
        }
    };
}

int_vector!(UVec2, u32, UVec2, IVec2);
int_vector!(UVec3, u32, UVec3, IVec3);
int_vector!(UVec4, u32, UVec4, IVec4);
int_vector!(IVec2, i32, UVec2, IVec2);
int_vector!(IVec3, i32, UVec3, IVec3);
int_vector!(IVec4, i32, UVec4, IVec4);

#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn add<A: RtAdd<B>, B>(a: A, b: B) -> A::Output {
    a.add(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn sub<A: RtSub<B>, B>(a: A, b: B) -> A::Output {
    a.sub(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn mul<A: RtMul<B>, B>(a: A, b: B) -> A::Output {
    a.mul(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn div<A: RtDiv<B>, B>(a: A, b: B) -> A::Output {
    a.div(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn rem<A: RtRem<B>, B>(a: A, b: B) -> A::Output {
    a.rem(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn shl<A: RtShift<B>, B>(a: A, b: B) -> A {
    a.shl(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn shr<A: RtShift<B>, B>(a: A, b: B) -> A {
    a.shr(b)
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn neg<A: RtNeg>(a: A) -> A::Output {
    a.neg()
}

/// `x.abs()`: `i32::MIN.abs()` is `i32::MIN`, as on the GPU.
#[doc(hidden)]
trait RtAbs {
    fn rt_abs(self) -> Self;
}
impl RtAbs for i32 {
    #[track_caller]
    #[inline(always)]
    fn rt_abs(self) -> i32 {
        overflowed(self.overflowing_abs())
    }
}
macro_rules! abs_via {
    ($($t:ty),*) => {$(
        impl RtAbs for $t {
            #[track_caller]
    #[inline(always)]
            fn rt_abs(self) -> $t {
                <$t>::abs(self)
            }
        }
    )*};
}
abs_via!(f32, Vec2, Vec3, Vec4);
// glam takes matrices by reference: `m.abs()`.
macro_rules! abs_mat {
    ($($t:ty),*) => {$(
        impl RtAbs for $t {
            #[inline(always)]
            fn rt_abs(self) -> $t {
                <$t>::abs(&self)
            }
        }
    )*};
}
abs_mat!(Mat2, Mat3, Mat4);
macro_rules! abs_ivec {
    ($($t:ty),*) => {$(
        impl RtAbs for $t {
            #[track_caller]
    #[inline(always)]
            fn rt_abs(self) -> $t {
                let mut a = self.to_array();
                for x in a.iter_mut() {
                    *x = x.rt_abs();
                }
                <$t>::from_array(a)
            }
        }
    )*};
}
abs_ivec!(IVec2, IVec3, IVec4);

/// `x.clamp(lo, hi)`: WGSL's `min(max(x, lo), hi)` where Rust would panic
/// (`lo > hi`, or a NaN bound); Rust's `clamp` otherwise.
#[doc(hidden)]
trait RtClamp: Sized {
    fn rt_clamp(self, lo: Self, hi: Self) -> Self;
}
macro_rules! clamp_scalar {
    ($($t:ty),*) => {$(
        impl RtClamp for $t {
            #[track_caller]
    #[inline(always)]
            fn rt_clamp(self, lo: $t, hi: $t) -> $t {
                if lo <= hi { <$t>::clamp(self, lo, hi) } else { self.max(lo).min(hi) }
            }
        }
    )*};
}
clamp_scalar!(f32, u32, i32);
macro_rules! clamp_vector {
    ($($t:ty),*) => {$(
        impl RtClamp for $t {
            #[track_caller]
    #[inline(always)]
            fn rt_clamp(self, lo: $t, hi: $t) -> $t {
                let (x, lo, hi) = (self.to_array(), lo.to_array(), hi.to_array());
                let mut i = 0;
                <$t>::from_array(x.map(|x| {
                    i += 1;
                    RtClamp::rt_clamp(x, lo[i - 1], hi[i - 1])
                }))
            }
        }
    )*};
}
clamp_vector!(Vec2, Vec3, Vec4, UVec2, UVec3, UVec4, IVec2, IVec3, IVec4);

/// `a op= b`: `b` is evaluated by the caller before `a` is borrowed, as for
/// Rust's primitive types. Floats, their vectors and matrices use std's
/// compound operator; the integer types the arithmetic one of this
/// module, then assign; a user's type its own `AddAssign` (the macro of
/// `#[rt_impl] impl AddAssign for T` implements the trait for `T`).
macro_rules! assign {
    ($name:ident, $assign:ident, $core:ident, $trait:ident, $method:ident, $message:literal) => {
        #[doc(hidden)]
        #[diagnostic::on_unimplemented(message = $message)]
        pub trait $assign<R> {
            fn $name(&mut self, r: R);
        }
        #[diagnostic::do_not_recommend]
        impl<A: Plain + core::ops::$core<B>, B> $assign<B> for A {
            #[track_caller]
            #[inline(always)]
            fn $name(&mut self, r: B) {
                core::ops::$core::$name(self, r)
            }
        }
        assign!(@int $name, $assign, $trait, $method; u32, i32, usize, UVec2, UVec3, UVec4, IVec2, IVec3, IVec4);
        #[doc(hidden)]
        #[track_caller]
        #[inline(always)]
        pub fn $name<A: $assign<B>, B>(a: &mut A, b: B) {
            a.$name(b)
        }
    };
    (@int $name:ident, $assign:ident, $trait:ident, $method:ident; $($t:ty),*) => {$(
        #[diagnostic::do_not_recommend]
        impl<B> $assign<B> for $t
        where
            $t: $trait<B, Output = $t>,
        {
            #[track_caller]
            #[inline(always)]
            fn $name(&mut self, r: B) {
                *self = (*self).$method(r);
            }
        }
    )*};
}
assign!(add_assign, RtAddAssign, AddAssign, RtAdd, add, "cannot add-assign `{R}` to `{Self}`");
assign!(sub_assign, RtSubAssign, SubAssign, RtSub, sub, "cannot subtract-assign `{R}` from `{Self}`");
assign!(mul_assign, RtMulAssign, MulAssign, RtMul, mul, "cannot multiply-assign `{Self}` by `{R}`");
assign!(div_assign, RtDivAssign, DivAssign, RtDiv, div, "cannot divide-assign `{Self}` by `{R}`");
assign!(
    rem_assign,
    RtRemAssign,
    RemAssign,
    RtRem,
    rem,
    "cannot calculate and assign the remainder of `{Self}` divided by `{R}`"
);

#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn shl_assign<A: RtShift<B> + Copy, B>(a: &mut A, b: B) {
    *a = (*a).shl(b);
}
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn shr_assign<A: RtShift<B> + Copy, B>(a: &mut A, b: B) {
    *a = (*a).shr(b);
}

#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn at<C: RtIndex<I> + ?Sized, I>(c: &C, i: I) -> &C::Output {
    c.at(i)
}

#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn at_mut<C: RtIndexMut<I> + ?Sized, I>(c: &mut C, i: I) -> &mut C::Output {
    c.at_mut(i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_wrap_and_divide_as_the_gpu_does() {
        assert_eq!(mul(0x9e37_79b9u32, 0x9e37_79b9u32), 0xe35e_67b1);
        assert_eq!(div(0x9e37_79b9u32, 0), 0x9e37_79b9);
        assert_eq!(rem(7u32, 0), 0);
        assert_eq!(div(i32::MIN, -1), i32::MIN);
        assert_eq!(rem(i32::MIN, -1), 0);
        assert_eq!(div(i32::MIN, 0), i32::MIN);
        assert_eq!(rem(-7i32, 0), 0);
        assert_eq!(shl(0x9e37_79b9u32, 33u32), 0x3c6e_f372);
        assert_eq!(shr(i32::MIN, 33u32), -0x4000_0000);
        assert_eq!(shl(i32::MIN, 33u32), 0);
        assert_eq!(neg(i32::MIN), i32::MIN);
        assert_eq!(sub(0u32, 0x9e37_79b9), 0x61c8_8647);
        assert_eq!(mul(i32::MIN, i32::MIN), 0);
        assert_eq!(add(usize::MAX >> 32, 1), 0, "usize wraps at 32 bits");
        assert_eq!(div(UVec3::new(6, 7, 8), UVec3::new(2, 0, 3)), UVec3::new(3, 7, 2));
        assert_eq!(rem(IVec2::new(i32::MIN, 5), -1), IVec2::new(0, 0));
        assert_eq!(mul(2u32, UVec2::new(u32::MAX, 3)), UVec2::new(u32::MAX - 1, 6));
        assert_eq!(neg(IVec2::new(i32::MIN, 1)), IVec2::new(i32::MIN, -1));
        assert_eq!(shl(UVec2::new(1, 1), UVec2::new(33, 2)), UVec2::new(2, 4));
        assert_eq!(Gpu(i32::MIN).abs(), i32::MIN);
        assert_eq!(Gpu(IVec2::new(i32::MIN, -3)).abs(), IVec2::new(i32::MIN, 3));
        assert_eq!(Gpu(5u32).clamp(7, 3), 3, "min(max(5, 7), 3)");
        assert_eq!(Gpu(5i32).clamp(1, 9), 5);
        assert_eq!(Gpu(Vec2::new(0.5, 2.0)).clamp(Vec2::ZERO, Vec2::ONE), Vec2::new(0.5, 1.0));
        assert_eq!(Gpu(0.5f32).clamp(f32::NAN, 1.0), 0.5);
    }

    #[test]
    fn floats_keep_their_operators() {
        assert_eq!(mul(Vec3::ONE, 2.0), Vec3::splat(2.0));
        assert_eq!(mul(2.0, Vec3::ONE), Vec3::splat(2.0));
        assert_eq!(div(1.0f32, 0.0), f32::INFINITY);
        assert_eq!(neg(Vec2::X), -Vec2::X);
        let mut v = Vec3::ONE;
        mul_assign(&mut v, 3.0);
        add_assign(&mut v, Vec3::X);
        assert_eq!(v, Vec3::new(4.0, 3.0, 3.0));
    }
}
