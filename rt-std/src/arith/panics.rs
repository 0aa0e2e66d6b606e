//! What the CPU copy of a program calls where Rust would panic and the GPU
//! raises `EXCEPTION_PANIC`: `o.unwrap()` and `o.expect(..)` of a `None`.
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
}
