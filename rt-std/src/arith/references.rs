//! The operators with a reference operand, as Rust's own operators take
//! them: `&f32 * f32`, `u32 % &u32`. Iterator chains hand their closures
//! references (`arr.iter().map(|v| v * v)`, `(0..n).filter(|i| i % 2 == 1)`),
//! and the CPU copy of a program calls these functions for `*`, `%` and
//! the rest, so each operator on a value works on a reference to it. (Not
//! recommended in rustc's messages: a user who adds an `i32` to an `f32`
//! should not read that `&f32` has an addition.)

use super::{RtAdd, RtDiv, RtMul, RtRem, RtSub};
use glam::{IVec2, IVec3, IVec4, Mat2, Mat3, Mat4, Quat, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4};

/// `&T op B` as `T op B`, for each operator.
macro_rules! reference_left {
    ($($t:ty),*) => {$(
        reference_left!(@op $t, RtAdd, add);
        reference_left!(@op $t, RtSub, sub);
        reference_left!(@op $t, RtMul, mul);
        reference_left!(@op $t, RtDiv, div);
        reference_left!(@op $t, RtRem, rem);
    )*};
    (@op $t:ty, $trait:ident, $method:ident) => {
        #[diagnostic::do_not_recommend]
        impl<B> $trait<B> for &$t
        where
            $t: $trait<B>,
        {
            type Output = <$t as $trait<B>>::Output;
            #[track_caller]
            #[inline(always)]
            fn $method(self, r: B) -> Self::Output {
                (*self).$method(r)
            }
        }
    };
}

/// `T op &T` as `T op T`, for the integer types (whose operators are this
/// crate's own; the float types' come from `core::ops`, which has these).
macro_rules! reference_right {
    ($($t:ty),*) => {$(
        reference_right!(@op $t, RtAdd, add);
        reference_right!(@op $t, RtSub, sub);
        reference_right!(@op $t, RtMul, mul);
        reference_right!(@op $t, RtDiv, div);
        reference_right!(@op $t, RtRem, rem);
    )*};
    (@op $t:ty, $trait:ident, $method:ident) => {
        #[diagnostic::do_not_recommend]
        impl<'a> $trait<&'a $t> for $t
        where
            $t: $trait<$t>,
        {
            type Output = <$t as $trait<$t>>::Output;
            #[track_caller]
            #[inline(always)]
            fn $method(self, r: &'a $t) -> Self::Output {
                self.$method(*r)
            }
        }
    };
}

reference_left!(f32, Vec2, Vec3, Vec4, Mat2, Mat3, Mat4, Quat);
reference_left!(i32, u32, usize, IVec2, IVec3, IVec4, UVec2, UVec3, UVec4);
reference_right!(i32, u32, usize, IVec2, IVec3, IVec4, UVec2, UVec3, UVec4);

#[cfg(test)]
mod tests {
    use crate::arith::{add, mul, rem, sub};

    #[test]
    fn references_operate_as_their_values() {
        let (a, b) = (3.5f32, 2.0f32);
        assert_eq!(mul(&a, b), 7.0);
        assert_eq!(mul(&a, &b), 7.0);
        assert_eq!(sub(&7u32, 9u32), 7u32.wrapping_sub(9), "wraps as the value does");
        assert_eq!(rem(9u32, &4u32), 1);
        assert_eq!(add(&glam::UVec2::ONE, &glam::UVec2::ONE), glam::UVec2::splat(2));
    }
}
