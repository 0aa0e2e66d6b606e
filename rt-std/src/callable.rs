//! Callable programs: functions a program calls through an id held in a
//! value (OptiX's bindless callable programs, `rtCallableProgramId`; OptiX
//! 7's direct callables).
//!
//! A callable is declared `#[rt_program(callable)]`, takes its arguments by
//! value and returns a value or nothing:
//!
//! ```ignore
//! #[rt_program(callable)]
//! fn lambert(n: Vec3, l: Vec3) -> Vec3 {
//!     Vec3::splat(n.dot(l).max(0.0))
//! }
//! ```
//!
//! A program holds a [`Callable<fn(A, ..) -> R>`](Callable) (a variable, a
//! buffer element, a payload or struct field) and calls it with
//! [`call`](Callable::call): `shade.call(n, l)`. The host gets the id of a
//! created callable program with `Context::callable_id`, which checks the
//! signature, and sets it like any value; a launch checks every
//! `Callable` variable against the program its id names. A program may
//! also make ids: [`Callable::NONE`], [`Callable::default()`] and
//! [`Callable::from_id`] (an id kept as a `u32`), with the signature named
//! (`Callable::<fn(u32) -> u32>::from_id(id)`) or known from a `let`'s type
//! or a parameter's.
//!
//! On the GPU each signature is one `switch` over the context's callables
//! of that signature; on the CPU the call is a direct call of the Rust
//! function. Either way an id that names no callable of the signature (zero,
//! [`Callable::NONE`], an id from elsewhere) raises
//! [`EXCEPTION_PROGRAM_ID_INVALID`](crate::EXCEPTION_PROGRAM_ID_INVALID) and
//! the call returns the zero value of its result.
//!
//! A callable may read `#[var]` variables, resolved as OptiX resolves a
//! bindless callable program's: in the callable program's own scope
//! (`Context::set_var(program, ..)`), then the context's; never the
//! caller's geometry instance or material. They are parameters like a
//! program's and not part of the signature: `fn tint(c: Vec3, #[var]
//! strength: f32) -> Vec3` is a `Callable<fn(Vec3) -> Vec3>`.
//!
//! Callables do not trace rays; they may call helpers, other callables,
//! `launch_index`, `launch_dim`, `rt_throw` and `rt_printf!`. WGSL has no
//! recursion, so no callable calls itself: a callable may call callables
//! of its own signature (a `blend` of two BRDFs), but a call through an id
//! of its own program raises
//! [`EXCEPTION_PROGRAM_ID_INVALID`](crate::EXCEPTION_PROGRAM_ID_INVALID) and
//! returns zero, on every backend; and callables of two or more programs
//! that may call each other (`a` calls a signature of `b`'s, `b` one of
//! `a`'s) are a cycle, which a launch refuses naming it.

use crate::data::RtData;
use crate::program::{LayoutKind, TypeLayout};
use core::marker::PhantomData;

/// The id of a callable program of signature `F` (`fn(Vec3, Vec3) -> Vec3`):
/// one `u32` word, 0 for none.
///
/// Program kinds: all but bounding_box may call it.
#[doc(alias = "rtCallableProgramId")]
#[doc(alias = "rtCallableProgram")]
#[repr(transparent)]
pub struct Callable<F> {
    id: u32,
    signature: PhantomData<fn() -> F>,
}

impl<F> Callable<F> {
    /// No callable: calling it raises
    /// [`EXCEPTION_PROGRAM_ID_INVALID`](crate::EXCEPTION_PROGRAM_ID_INVALID).
    pub const NONE: Self = Self::from_id(0);

    /// The callable of id `id` (as `Context::callable_id` gives it, or read
    /// from a buffer of ids). Nothing is checked until a call.
    pub const fn from_id(id: u32) -> Self {
        Callable { id, signature: PhantomData }
    }

    /// The id.
    pub const fn id(self) -> u32 {
        self.id
    }
}

impl<F> Clone for Callable<F> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<F> Copy for Callable<F> {}

impl<F> PartialEq for Callable<F> {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id
    }
}

impl<F> Eq for Callable<F> {}

impl<F> Default for Callable<F> {
    fn default() -> Self {
        Self::NONE
    }
}

impl<F> core::fmt::Debug for Callable<F> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "Callable({})", self.id)
    }
}

/// The layout every `Callable` shares: its signature is checked against
/// the id's program at launch, not by the layout's name.
pub const CALLABLE_LAYOUT: TypeLayout =
    TypeLayout { kind: LayoutKind::Callable(None), rust: "Callable", wgsl: "u32", words: 1, fields: &[] };

impl<F: 'static> RtData for Callable<F> {
    const LAYOUT: TypeLayout = CALLABLE_LAYOUT;

    fn write_words(&self, out: &mut [u32]) {
        out[0] = self.id;
    }

    fn read_words(words: &[u32]) -> Self {
        Self::from_id(words[0])
    }
}

/// The Rust function of callable `id` if it has type `F`.
fn target<F: Copy + 'static>(id: u32) -> Option<F> {
    let f = crate::cpu::callable(id)?;
    f.downcast_ref::<F>().copied()
}

/// What a call through an id of no callable of its signature returns,
/// after raising the exception.
fn invalid<R: Default>() -> R {
    crate::cpu::raise(crate::EXCEPTION_PROGRAM_ID_INVALID);
    R::default()
}

macro_rules! call_arity {
    ($($a:ident: $t:ident),*) => {
        impl<$($t: 'static,)* R: Default + 'static> Callable<fn($($t),*) -> R> {
            /// Calls the callable program this id names with these
            /// arguments (OptiX: calling an `rtCallableProgramId`; OptiX
            /// 7: `optixDirectCall`). An id of no callable of this
            /// signature raises
            /// [`EXCEPTION_PROGRAM_ID_INVALID`](crate::EXCEPTION_PROGRAM_ID_INVALID)
            /// and returns `R::default()` (zero).
            ///
            /// Program kinds: all but bounding_box.
            #[doc(alias = "optixDirectCall")]
            #[allow(clippy::too_many_arguments)]
            #[inline]
            pub fn call(self, $($a: $t),*) -> R {
                match target::<fn($($t),*) -> R>(self.id) {
                    Some(f) => crate::cpu::calling(self.id, || f($($a),*)),
                    None => invalid(),
                }
            }
        }
    };
}

call_arity!();
call_arity!(a0: A0);
call_arity!(a0: A0, a1: A1);
call_arity!(a0: A0, a1: A1, a2: A2);
call_arity!(a0: A0, a1: A1, a2: A2, a3: A3);
call_arity!(a0: A0, a1: A1, a2: A2, a3: A3, a4: A4);
call_arity!(a0: A0, a1: A1, a2: A2, a3: A3, a4: A4, a5: A5);
call_arity!(a0: A0, a1: A1, a2: A2, a3: A3, a4: A4, a5: A5, a6: A6);
call_arity!(a0: A0, a1: A1, a2: A2, a3: A3, a4: A4, a5: A5, a6: A6, a7: A7);
