//! The indexing traits behind `at` and `at_mut`, with the GPU's meaning:
//! local arrays and vectors clamp the index to the last element, buffers
//! raise the out-of-bounds exception through their own `Index`.

use glam::{IVec2, IVec3, IVec4, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4};

/// Indexing: local arrays and vectors clamp the index to the last element
/// (naga's `Restrict` policy); buffers keep their own `Index`, which raises
/// the out-of-bounds exception.
#[doc(hidden)]
#[diagnostic::on_unimplemented(message = "cannot index into a value of type `{Self}` with `{I}`")]
pub trait RtIndex<I> {
    type Output: ?Sized;
    fn at(&self, i: I) -> &Self::Output;
}

/// Indexing in a place that is written.
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "cannot assign through an index into `{Self}`",
    label = "`{Self}` is not writable",
    note = "a `Buffer` is read-only in ray programs: declare the variable as `RwBuffer`"
)]
pub trait RtIndexMut<I>: RtIndex<I> {
    fn at_mut(&mut self, i: I) -> &mut Self::Output;
}

impl<T, const N: usize> RtIndex<usize> for [T; N] {
    type Output = T;
    #[track_caller]
    #[inline(always)]
    fn at(&self, i: usize) -> &T {
        &self[i.min(N - 1)]
    }
}
impl<T, const N: usize> RtIndexMut<usize> for [T; N] {
    #[track_caller]
    #[inline(always)]
    fn at_mut(&mut self, i: usize) -> &mut T {
        &mut self[i.min(N - 1)]
    }
}

macro_rules! vector_index {
    ($v:ty, $s:ty, $n:literal) => {
        impl RtIndex<usize> for $v {
            type Output = $s;
            #[track_caller]
            #[inline(always)]
            fn at(&self, i: usize) -> &$s {
                &self[i.min($n - 1)]
            }
        }
        impl RtIndexMut<usize> for $v {
            #[track_caller]
            #[inline(always)]
            fn at_mut(&mut self, i: usize) -> &mut $s {
                &mut self[i.min($n - 1)]
            }
        }
    };
}
vector_index!(Vec2, f32, 2);
vector_index!(Vec3, f32, 3);
vector_index!(Vec4, f32, 4);
vector_index!(UVec2, u32, 2);
vector_index!(UVec3, u32, 3);
vector_index!(UVec4, u32, 4);
vector_index!(IVec2, i32, 2);
vector_index!(IVec3, i32, 3);
vector_index!(IVec4, i32, 4);

macro_rules! buffer_index {
    ($b:ident, $i:ty) => {
        impl<T: crate::RtData> RtIndex<$i> for crate::buffer::$b<T> {
            type Output = T;
            #[track_caller]
            #[inline(always)]
            fn at(&self, i: $i) -> &T {
                &self[i]
            }
        }
    };
    ($b:ident, $i:ty, mut) => {
        buffer_index!($b, $i);
        impl<T: crate::RtData> RtIndexMut<$i> for crate::buffer::$b<T> {
            #[track_caller]
            #[inline(always)]
            fn at_mut(&mut self, i: $i) -> &mut T {
                &mut self[i]
            }
        }
    };
}
buffer_index!(Buffer, u32);
buffer_index!(RwBuffer, u32, mut);
buffer_index!(Buffer2d, UVec2);
buffer_index!(RwBuffer2d, UVec2, mut);
buffer_index!(Buffer3d, UVec3);
buffer_index!(RwBuffer3d, UVec3, mut);

macro_rules! bindless_index {
    ($b:ident) => {
        impl<T: crate::RtData + Send + Sync> RtIndex<u32> for crate::bindless::$b<T> {
            type Output = T;
            #[track_caller]
            #[inline(always)]
            fn at(&self, i: u32) -> &T {
                &self[i]
            }
        }
    };
}
bindless_index!(BindlessBuffer);
bindless_index!(RwBindlessBuffer);

#[diagnostic::do_not_recommend]
impl<C: RtIndex<I> + ?Sized, I> RtIndex<I> for &C {
    type Output = C::Output;
    #[track_caller]
    #[inline(always)]
    fn at(&self, i: I) -> &C::Output {
        (**self).at(i)
    }
}

#[diagnostic::do_not_recommend]
impl<C: RtIndex<I> + ?Sized, I> RtIndex<I> for &mut C {
    type Output = C::Output;
    #[track_caller]
    #[inline(always)]
    fn at(&self, i: I) -> &C::Output {
        (**self).at(i)
    }
}

#[diagnostic::do_not_recommend]
impl<C: RtIndexMut<I> + ?Sized, I> RtIndexMut<I> for &mut C {
    #[track_caller]
    #[inline(always)]
    fn at_mut(&mut self, i: I) -> &mut C::Output {
        (**self).at_mut(i)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{add_assign, at, at_mut, shl_assign};
    use super::*;

    #[test]
    fn local_indices_clamp_to_the_last_element() {
        let mut arr = [1u32, 2, 3, 4];
        assert_eq!(*at(&arr, 4), 4);
        assert_eq!(*at(&arr, usize::MAX), 4);
        *at_mut(&mut arr, 9) = 7;
        assert_eq!(arr, [1, 2, 3, 7]);
        let v = Vec3::new(1.0, 2.0, 3.0);
        assert_eq!(*at(&v, 3), 3.0);
        let r = &arr;
        assert_eq!(*at(&r, 0), 1);
        let mut x = 5u32;
        add_assign(&mut x, u32::MAX);
        assert_eq!(x, 4);
        shl_assign(&mut x, 34);
        assert_eq!(x, 16);
    }
}
