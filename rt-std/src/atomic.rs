//! Atomic updates of buffer elements: `RwBuffer<T>::atomic_add` and the
//! rest (CUDA's `atomicAdd`, `atomicMin`, ... in OptiX programs), for
//! elements of `u32`, `i32` and `f32` ([`AtomicElement`]), the bitwise ones
//! and `atomic_sub` for `u32` and `i32` ([`AtomicInteger`]).
//!
//! Each update reads the element, combines it with the operand and writes
//! the result as one indivisible step, and returns the element's old
//! value, on both backends: the megakernel's WGSL atomics on the heap's
//! words, the CPU backend's [`core::sync::atomic::AtomicU32`] on the
//! element itself. Updates are relaxed: they order nothing else, so a
//! launch index reads another's updates only in a later launch.
//!
//! # Results
//! - Integer updates are exact, and so are their totals whatever order the
//!   launch indices run in: `u32` and `i32` `add` and `sub` wrap, `min` and
//!   `max` compare as the element type (unsigned or signed). A launch's
//!   final integer values are the same on every backend and every run.
//! - `f32` updates (`add`, `min`, `max`) are compare-exchange loops on the
//!   element's bits (WGSL has no float atomics). `min` and `max` keep the
//!   old value unless the operand compares below (above) it, so a NaN
//!   operand never lands and a NaN element stays. Float addition is not
//!   associative: a sum of many updates depends on the order they happened
//!   in, which varies between runs and backends. Each addition is rounded
//!   once; a sum of `n` values has at most the error of some order of
//!   summing them (about `n * f32::EPSILON` of the sum of magnitudes), and
//!   sums of integers below 2^24 are exact.
//! - `atomic_compare_exchange(i, current, new)` writes `new` if the element
//!   holds `current` (compared bit for bit, so `-0.0` and `0.0` differ and a
//!   NaN matches itself) and returns the old value either way: it succeeded
//!   exactly when that equals `current`'s bits.
//!
//! # Bounds and races
//! An index outside the buffer raises
//! [`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`](crate::EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
//! changes nothing and returns zero. Atomic updates of an element may race
//! with each other; a plain `load`, `store` or index of the same element in
//! the same launch while another launch index updates it is a race (see
//! [`crate::buffer`]).
//!
//! On the GPU, a megakernel whose programs update elements atomically
//! reads and writes its whole heap (variables, buffers, textures) through
//! relaxed atomic loads and stores, which may cost some speed; kernels
//! without atomics are unchanged.

use core::sync::atomic::{AtomicU32, Ordering::Relaxed};

use glam::UVec2;

use crate::buffer::{RwBuffer, RwBuffer2d};
use crate::data::RtData;

mod sealed {
    pub trait Sealed {}
    impl Sealed for u32 {}
    impl Sealed for i32 {}
    impl Sealed for f32 {}
}

/// An element type buffers update atomically: `u32`, `i32` or `f32`, one
/// 32-bit word. Sealed.
pub trait AtomicElement: RtData + Copy + sealed::Sealed {
    #[doc(hidden)]
    fn to_word(self) -> u32;
    #[doc(hidden)]
    fn from_word(w: u32) -> Self;
    #[doc(hidden)]
    fn sum(self, v: Self) -> Self;
    #[doc(hidden)]
    fn less(self, v: Self) -> bool;
}

/// An integer element type (`u32`, `i32`): it also has the bitwise
/// updates and `atomic_sub`. Sealed.
pub trait AtomicInteger: AtomicElement {
    #[doc(hidden)]
    fn difference(self, v: Self) -> Self;
}

impl AtomicElement for u32 {
    fn to_word(self) -> u32 {
        self
    }
    fn from_word(w: u32) -> Self {
        w
    }
    fn sum(self, v: Self) -> Self {
        self.wrapping_add(v)
    }
    fn less(self, v: Self) -> bool {
        self < v
    }
}

impl AtomicElement for i32 {
    fn to_word(self) -> u32 {
        self as u32
    }
    fn from_word(w: u32) -> Self {
        w as i32
    }
    fn sum(self, v: Self) -> Self {
        self.wrapping_add(v)
    }
    fn less(self, v: Self) -> bool {
        self < v
    }
}

impl AtomicElement for f32 {
    fn to_word(self) -> u32 {
        self.to_bits()
    }
    fn from_word(w: u32) -> Self {
        f32::from_bits(w)
    }
    fn sum(self, v: Self) -> Self {
        self + v
    }
    fn less(self, v: Self) -> bool {
        self < v
    }
}

impl AtomicInteger for u32 {
    fn difference(self, v: Self) -> Self {
        self.wrapping_sub(v)
    }
}

impl AtomicInteger for i32 {
    fn difference(self, v: Self) -> Self {
        self.wrapping_sub(v)
    }
}

/// The element at `p` as an atomic word.
///
/// # Safety
/// `p` is a live element of a buffer handle (aligned for `T`, a 32-bit
/// type, so for `AtomicU32`); every concurrent access to it is atomic (the
/// module's race rule).
unsafe fn word<'a, T: AtomicElement>(p: *mut T) -> &'a AtomicU32 {
    // SAFETY: as the caller promises; `T` is 4 bytes with 4-byte alignment.
    unsafe { AtomicU32::from_ptr(p.cast()) }
}

/// Applies `f` to the element at `p` in one step; returns the old value
/// (zero when `p` is `None`: out of bounds, the exception raised).
fn update<T: AtomicElement>(p: Option<*mut T>, f: impl Fn(T) -> T) -> T {
    let Some(p) = p else { return T::from_word(0) };
    // SAFETY: `p` came from the handle's bounds check.
    let w = unsafe { word(p) };
    let old = w.fetch_update(Relaxed, Relaxed, |old| Some(f(T::from_word(old)).to_word()));
    T::from_word(old.unwrap_or_else(|old| old))
}

fn exchange<T: AtomicElement>(p: Option<*mut T>, v: T) -> T {
    let Some(p) = p else { return T::from_word(0) };
    // SAFETY: as in `update`.
    T::from_word(unsafe { word(p) }.swap(v.to_word(), Relaxed))
}

fn compare_exchange<T: AtomicElement>(p: Option<*mut T>, current: T, new: T) -> T {
    let Some(p) = p else { return T::from_word(0) };
    // SAFETY: as in `update`.
    let r = unsafe { word(p) }.compare_exchange(current.to_word(), new.to_word(), Relaxed, Relaxed);
    T::from_word(r.unwrap_or_else(|old| old))
}

macro_rules! atomic_methods {
    ($buffer:ident, $index:ty, $what:literal) => {
        impl<T: AtomicElement> $buffer<T> {
            #[doc = concat!("Adds `v` to the element at `", $what, "` atomically; returns the old value.")]
            /// Integers wrap; see the [module docs](crate::atomic) for
            /// what `f32` sums guarantee.
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicAdd")]
            pub fn atomic_add(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| old.sum(v))
            }

            #[doc = concat!("Makes the element at `", $what, "` the smaller of it and `v`, atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicMin")]
            pub fn atomic_min(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| if v.less(old) { v } else { old })
            }

            #[doc = concat!("Makes the element at `", $what, "` the larger of it and `v`, atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicMax")]
            pub fn atomic_max(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| if old.less(v) { v } else { old })
            }

            #[doc = concat!("Writes `v` at `", $what, "` atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicExch")]
            pub fn atomic_exchange(&self, i: $index, v: T) -> T {
                exchange(self.element(i), v)
            }

            #[doc = concat!("Writes `new` at `", $what, "` if the element holds `current` (bit for bit), atomically; returns the old value, equal to `current` exactly when it wrote.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicCAS")]
            pub fn atomic_compare_exchange(&self, i: $index, current: T, new: T) -> T {
                compare_exchange(self.element(i), current, new)
            }
        }

        impl<T: AtomicInteger> $buffer<T> {
            #[doc = concat!("Subtracts `v` from the element at `", $what, "` atomically (wrapping); returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicSub")]
            pub fn atomic_sub(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| old.difference(v))
            }

            #[doc = concat!("Bitwise-ands `v` into the element at `", $what, "` atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicAnd")]
            pub fn atomic_and(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| T::from_word(old.to_word() & v.to_word()))
            }

            #[doc = concat!("Bitwise-ors `v` into the element at `", $what, "` atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicOr")]
            pub fn atomic_or(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| T::from_word(old.to_word() | v.to_word()))
            }

            #[doc = concat!("Bitwise-xors `v` into the element at `", $what, "` atomically; returns the old value.")]
            ///
            /// Program kinds: all.
            #[doc(alias = "atomicXor")]
            pub fn atomic_xor(&self, i: $index, v: T) -> T {
                update(self.element(i), |old| T::from_word(old.to_word() ^ v.to_word()))
            }
        }
    };
}

atomic_methods!(RwBuffer, u32, "i");
atomic_methods!(RwBuffer2d, UVec2, "idx");

#[cfg(test)]
mod tests {
    use super::*;

    fn buffer<T: RtData>(v: &mut Vec<T>) -> RwBuffer<T> {
        let len = v.len() as u32 - 1;
        // SAFETY: `v` holds `len` elements and the sink, and outlives the
        // handle in each test.
        unsafe { RwBuffer::from_raw_parts(v.as_mut_ptr(), len) }
    }

    #[test]
    fn integer_updates_return_the_old_value() {
        let mut v = vec![5u32, 0];
        let b = buffer(&mut v);
        assert_eq!(b.atomic_add(0, 3), 5);
        assert_eq!(b.atomic_sub(0, 10), 8);
        assert_eq!(b.load(0), 8u32.wrapping_sub(10));
        assert_eq!(b.atomic_exchange(0, 0b1100), u32::MAX - 1);
        assert_eq!(b.atomic_and(0, 0b1010), 0b1100);
        assert_eq!(b.atomic_or(0, 0b0001), 0b1000);
        assert_eq!(b.atomic_xor(0, 0b1111), 0b1001);
        assert_eq!(b.atomic_min(0, 2), 0b0110);
        assert_eq!(b.atomic_max(0, 9), 2);
        assert_eq!(b.atomic_compare_exchange(0, 8, 1), 9);
        assert_eq!(b.atomic_compare_exchange(0, 9, 1), 9);
        assert_eq!(b.load(0), 1);
        let mut s = vec![-3i32, 0];
        let b = buffer(&mut s);
        assert_eq!(b.atomic_min(0, -7), -3);
        assert_eq!(b.atomic_max(0, 4), -7);
        assert_eq!(b.load(0), 4);
    }

    #[test]
    fn float_updates_compare_as_floats_and_exchange_bits() {
        let mut v = vec![1.5f32, 0.0];
        let b = buffer(&mut v);
        assert_eq!(b.atomic_add(0, 0.25), 1.5);
        assert_eq!(b.atomic_min(0, f32::NAN), 1.75);
        assert_eq!(b.atomic_max(0, -1.0), 1.75);
        assert_eq!(b.atomic_exchange(0, 0.0), 1.75);
        assert_eq!(b.atomic_compare_exchange(0, -0.0, 2.0).to_bits(), 0.0f32.to_bits());
        assert_eq!(b.load(0).to_bits(), 0.0f32.to_bits());
    }

    #[test]
    fn out_of_bounds_changes_nothing() {
        let mut v = vec![7u32, 0];
        let b = buffer(&mut v);
        assert_eq!(b.atomic_add(1, 1), 0);
        assert_eq!(v, [7, 0]);
    }

    #[test]
    fn concurrent_adds_are_all_counted() {
        let mut v = vec![0u32, 0];
        let b = buffer(&mut v);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| {
                    for i in 0..10_000 {
                        b.atomic_add(0, i % 3);
                    }
                });
            }
        });
        assert_eq!(b.load(0), 4 * (0..10_000u32).map(|i| i % 3).sum::<u32>());
    }
}
