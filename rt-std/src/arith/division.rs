//! The dividing methods of the integers and their vectors, as the GPU
//! computes them (`rt-compiler`'s `lower/builtins/int_division.rs` lowers
//! the same methods): `div_euclid`, `rem_euclid`, `wrapping_div` and
//! `saturating_div`. Rust panics at a zero divisor (and `div_euclid` at
//! `i32::MIN / -1`); here a zero divisor is read as one, which gives what
//! `/` and `%` give on the GPU (`a` for the quotients, 0 for the
//! remainder), raising `EXCEPTION_INTEGER_DIVIDE_BY_ZERO` when integer
//! exceptions are on, as the operators do. `i32::MIN.div_euclid(-1)`
//! wraps to `i32::MIN` (raising `EXCEPTION_INTEGER_OVERFLOW` when they are
//! on), as `/` does; `wrapping_div` and `saturating_div` are defined there
//! and raise nothing. Floats keep Rust's meaning (only `div_euclid` and
//! `rem_euclid` exist for them).

use super::{overflowed, trap};
use glam::{IVec2, IVec3, IVec4, UVec2, UVec3, UVec4};

/// The dividing methods, per type.
#[doc(hidden)]
pub(super) trait RtDivide: Sized {
    fn rt_div_euclid(self, b: Self) -> Self;
    fn rt_rem_euclid(self, b: Self) -> Self;
    fn rt_wrapping_div(self, b: Self) -> Self;
    fn rt_saturating_div(self, b: Self) -> Self;
}

macro_rules! int_scalar {
    ($t:ty) => {
        impl RtDivide for $t {
            #[track_caller]
            #[inline(always)]
            fn rt_div_euclid(self, b: $t) -> $t {
                overflowed(self.overflowing_div_euclid(nonzero(b)))
            }
            #[track_caller]
            #[inline(always)]
            fn rt_rem_euclid(self, b: $t) -> $t {
                // `i32::MIN.rem_euclid(-1)` is 0: nothing to report.
                self.wrapping_rem_euclid(nonzero(b))
            }
            #[track_caller]
            #[inline(always)]
            fn rt_wrapping_div(self, b: $t) -> $t {
                self.wrapping_div(nonzero(b))
            }
            #[track_caller]
            #[inline(always)]
            fn rt_saturating_div(self, b: $t) -> $t {
                self.saturating_div(nonzero(b))
            }
        }
    };
}

/// A zero divisor: trapped, and read as one.
#[track_caller]
#[inline(always)]
fn nonzero<T: PartialEq + From<u8>>(b: T) -> T {
    if b == T::from(0) {
        trap(crate::EXCEPTION_INTEGER_DIVIDE_BY_ZERO);
        T::from(1)
    } else {
        b
    }
}

int_scalar!(i32);
int_scalar!(u32);

/// Per component, as glam's vector methods are.
macro_rules! int_vector {
    ($($v:ty),*) => {$(
        impl RtDivide for $v {
            #[track_caller]
            #[inline(always)]
            fn rt_div_euclid(self, b: $v) -> $v {
                per_component(self, b, RtDivide::rt_div_euclid)
            }
            #[track_caller]
            #[inline(always)]
            fn rt_rem_euclid(self, b: $v) -> $v {
                per_component(self, b, RtDivide::rt_rem_euclid)
            }
            #[track_caller]
            #[inline(always)]
            fn rt_wrapping_div(self, b: $v) -> $v {
                per_component(self, b, RtDivide::rt_wrapping_div)
            }
            #[track_caller]
            #[inline(always)]
            fn rt_saturating_div(self, b: $v) -> $v {
                per_component(self, b, RtDivide::rt_saturating_div)
            }
        }
    )*};
}

int_vector!(IVec2, IVec3, IVec4, UVec2, UVec3, UVec4);

/// `f(a.x, b.x)`, `f(a.y, b.y)`, ... of a glam vector.
#[track_caller]
#[inline(always)]
fn per_component<V: Components>(a: V, b: V, f: fn(V::Scalar, V::Scalar) -> V::Scalar) -> V {
    let (mut a_, b_) = (a.components(), b.components());
    for (x, y) in a_.as_mut().iter_mut().zip(b_.as_ref()) {
        *x = f(*x, *y);
    }
    V::from_components(a_)
}

/// A glam integer vector as its array of components.
trait Components {
    type Scalar: Copy;
    type Array: AsRef<[Self::Scalar]> + AsMut<[Self::Scalar]>;
    fn components(self) -> Self::Array;
    fn from_components(a: Self::Array) -> Self;
}

macro_rules! components {
    ($($v:ty, $s:ty, $n:literal);*) => {$(
        impl Components for $v {
            type Scalar = $s;
            type Array = [$s; $n];
            #[inline(always)]
            fn components(self) -> [$s; $n] {
                self.to_array()
            }
            #[inline(always)]
            fn from_components(a: [$s; $n]) -> $v {
                <$v>::from_array(a)
            }
        }
    )*};
}

components!(IVec2, i32, 2; IVec3, i32, 3; IVec4, i32, 4; UVec2, u32, 2; UVec3, u32, 3; UVec4, u32, 4);

#[cfg(test)]
mod tests {
    use super::*;

    fn div_euclid<A: RtDivide>(a: A, b: A) -> A {
        a.rt_div_euclid(b)
    }
    fn rem_euclid<A: RtDivide>(a: A, b: A) -> A {
        a.rt_rem_euclid(b)
    }
    fn wrapping_div<A: RtDivide>(a: A, b: A) -> A {
        a.rt_wrapping_div(b)
    }
    fn saturating_div<A: RtDivide>(a: A, b: A) -> A {
        a.rt_saturating_div(b)
    }

    #[test]
    fn zero_divisors_and_the_overflowing_quotient_answer_as_the_gpu_does() {
        assert_eq!(div_euclid(7i32, 0), 7);
        assert_eq!(rem_euclid(7i32, 0), 0);
        assert_eq!(wrapping_div(-7i32, 0), -7);
        assert_eq!(saturating_div(-7i32, 0), -7);
        assert_eq!(div_euclid(i32::MIN, -1), i32::MIN);
        assert_eq!(rem_euclid(i32::MIN, -1), 0);
        assert_eq!(wrapping_div(i32::MIN, -1), i32::MIN);
        assert_eq!(saturating_div(i32::MIN, -1), i32::MAX);
        assert_eq!(div_euclid(-7i32, 2), -4);
        assert_eq!(rem_euclid(-7i32, 2), 1);
        assert_eq!(div_euclid(-7i32, -2), 4);
        assert_eq!(rem_euclid(-1i32, i32::MIN), i32::MAX);
        assert_eq!(div_euclid(9u32, 0), 9);
        assert_eq!(rem_euclid(9u32, 0), 0);
        assert_eq!(div_euclid(IVec3::new(-7, 5, 3), IVec3::new(2, 0, -1)), IVec3::new(-4, 5, -3));
        assert_eq!(rem_euclid(UVec2::new(9, 9), UVec2::new(4, 0)), UVec2::new(1, 0));
    }
}
