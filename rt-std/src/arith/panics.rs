//! What the CPU copy of a program calls where Rust would panic and the GPU
//! raises `EXCEPTION_PANIC`: `o.unwrap()` and `o.expect(..)` of a `None`,
//! and a failed `debug_assert!` (with debug assertions on).
//! The exception records the caller's file and line; the program goes on
//! with the value the GPU has, zero.

use crate::RtData;

/// `o.unwrap()`, `o.expect(msg)`: the value, or zero after raising
/// `EXCEPTION_PANIC` at the caller.
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`unwrap` and `expect` in ray programs are `Option`'s, of a value the GPU holds"
)]
pub trait RtUnwrap {
    type Output;
    #[track_caller]
    fn unwrap_or_raise(self) -> Self::Output;
}

impl<T: RtData> RtUnwrap for Option<T> {
    type Output = T;
    #[track_caller]
    #[inline(always)]
    fn unwrap_or_raise(self) -> T {
        match self {
            Some(v) => v,
            None => {
                crate::cpu::raise_here(crate::EXCEPTION_PANIC);
                zero()
            }
        }
    }
}

/// The value whose words are all zero: what the GPU's `Option` holds in a
/// `None`.
fn zero<T: RtData>() -> T {
    T::read_words(&vec![0u32; T::LAYOUT.words as usize])
}

#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn unwrap<O: RtUnwrap>(o: O) -> O::Output {
    o.unwrap_or_raise()
}

/// `o.expect(msg)`: as [`unwrap`]; the message is the CPU's alone (the GPU
/// has no strings), and the exception's record has the call's place.
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn expect<O: RtUnwrap>(o: O, _msg: &str) -> O::Output {
    o.unwrap_or_raise()
}

/// A failed `debug_assert!(cond)` of a ray program: `EXCEPTION_PANIC` at
/// the caller, and the program goes on, as on the GPU.
#[doc(hidden)]
#[track_caller]
#[inline(always)]
pub fn debug_assert_failed() {
    crate::cpu::raise_here(crate::EXCEPTION_PANIC);
}

/// `debug_assert!(cond)` and `debug_assert!(cond, "why")` in the CPU copy
/// of a ray program: with debug assertions on in the crate that writes it
/// (this expands there), a false `cond` raises `EXCEPTION_PANIC` where the
/// assertion is; off, `cond` is not evaluated, as Rust's.
#[doc(hidden)]
#[macro_export]
macro_rules! __rt_debug_assert {
    // (A message with arguments is the lowering's error, not this one's.)
    ($cond:expr $(, $($msg:tt)*)?) => {
        if ::core::cfg!(debug_assertions) && !$cond {
            $crate::arith::debug_assert_failed();
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::ExecutionContext;

    #[test]
    fn a_none_raises_at_the_caller_and_gives_zero() {
        let ((got, line), ctx) =
            crate::cpu::with_context(ExecutionContext::default(), || (unwrap(None::<glam::Vec3>), line!()));
        assert_eq!(got, glam::Vec3::ZERO);
        assert_eq!(ctx.pending_exception, Some(crate::EXCEPTION_PANIC));
        let at = ctx.pending_location.expect("a location");
        assert_eq!((at.file(), at.line()), (file!(), line));
        let (got, ctx) = crate::cpu::with_context(ExecutionContext::default(), || unwrap(Some(7u32)));
        assert_eq!((got, ctx.pending_exception), (7, None));
    }

    #[test]
    fn a_failed_debug_assertion_raises_at_the_assertion() {
        let ((), ctx) =
            crate::cpu::with_context(ExecutionContext::default(), || crate::__rt_debug_assert!(1 > 2, "no"));
        // This crate's tests are built with debug assertions on or off.
        if cfg!(debug_assertions) {
            assert_eq!(ctx.pending_exception, Some(crate::EXCEPTION_PANIC));
            assert_eq!(ctx.pending_location.map(|at| at.line()), Some(line!() - 4));
        } else {
            assert_eq!(ctx.pending_exception, None);
        }
        let ((), ctx) = crate::cpu::with_context(ExecutionContext::default(), || crate::__rt_debug_assert!(2 > 1));
        assert_eq!(ctx.pending_exception, None);
    }
}
