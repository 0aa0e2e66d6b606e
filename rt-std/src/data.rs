//! [`RtData`]: values that live in the runtime's buffer heap and variable
//! records, with one layout for CPU and GPU (packed 32-bit words).

use crate::layout::{TriangleBuiltin, TriangleBuiltins, TypeLayout};
use glam::{IVec2, IVec3, IVec4, Mat2, Mat3, Mat4, UVec2, UVec3, UVec4, Vec2, Vec3, Vec4};

/// A type that programs can read from variables and buffers.
///
/// Layout: fields packed in declaration order, each scalar one 32-bit word,
/// no padding. `#[rt_struct]`, `#[rt_payload]` and `#[rt_attributes]`
/// implement it for user structs, `#[rt_enum]` for user enums.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not declared for ray programs",
    label = "mark `{Self}` with #[rt_struct] (or #[rt_payload], #[rt_attributes], #[rt_enum])"
)]
pub trait RtData: Copy + 'static {
    /// Spelling and size of the type.
    const LAYOUT: TypeLayout;
    /// Writes `LAYOUT.words` words to the start of `out`.
    fn write_words(&self, out: &mut [u32]);
    /// Reads a value from the first `LAYOUT.words` words of `words`.
    fn read_words(words: &[u32]) -> Self;
    /// [`read_words`](Self::read_words) into `self`. Structs overwrite their
    /// fields one by one: assigning a whole value built on the stack copies
    /// it in loads wider than its fields were stored with, which stall.
    #[inline]
    fn read_words_into(&mut self, words: &[u32]) {
        *self = Self::read_words(words);
    }
}

use crate::layout::{LayoutKind, ScalarKind};

macro_rules! scalar {
    ($t:ty, $k:ident, $rust:literal, $wgsl:literal, |$v:ident| $to:expr, |$w:ident| $from:expr) => {
        impl RtData for $t {
            const LAYOUT: TypeLayout = TypeLayout {
                kind: LayoutKind::Scalar(ScalarKind::$k),
                rust: $rust,
                wgsl: $wgsl,
                words: 1,
                fields: &[],
            };
            #[inline]
            fn write_words(&self, out: &mut [u32]) {
                let $v = *self;
                out[0] = $to;
            }
            #[inline]
            fn read_words(words: &[u32]) -> Self {
                let $w = words[0];
                $from
            }
        }
    };
}

scalar!(f32, F32, "f32", "f32", |v| v.to_bits(), |w| f32::from_bits(w));
scalar!(i32, I32, "i32", "i32", |v| v as u32, |w| w as i32);
scalar!(u32, U32, "u32", "u32", |v| v, |w| w);
scalar!(bool, Bool, "bool", "bool", |v| v as u32, |w| w != 0);

// Whole values go through fixed-size chunks: a copy over however many words
// the slice has becomes a `memcpy` call of that length, whose stores the
// value's wider loads then wait on (a store-forwarding stall per read). A
// slice shorter than the value, which the runtime never passes, takes what
// fits.
macro_rules! vector {
    ($t:ty, $s:ty, $k:ident, $n:literal, $rust:literal, $wgsl:literal) => {
        impl RtData for $t {
            const LAYOUT: TypeLayout = TypeLayout {
                kind: LayoutKind::Vector { scalar: ScalarKind::$k, len: $n },
                rust: $rust,
                wgsl: $wgsl,
                words: $n,
                fields: &[],
            };
            #[inline]
            fn write_words(&self, out: &mut [u32]) {
                let a: [$s; $n] = (*self).into();
                match out.first_chunk_mut::<$n>() {
                    Some(o) => {
                        for (o, v) in o.iter_mut().zip(a) {
                            v.write_words(core::slice::from_mut(o));
                        }
                    }
                    None => {
                        for (o, v) in out.iter_mut().zip(a) {
                            v.write_words(core::slice::from_mut(o));
                        }
                    }
                }
            }
            #[inline]
            fn read_words(words: &[u32]) -> Self {
                if let Some(w) = words.first_chunk::<$n>() {
                    let a: [$s; $n] = core::array::from_fn(|i| <$s>::read_words(core::slice::from_ref(&w[i])));
                    return a.into();
                }
                let mut a = [<$s>::default(); $n];
                for (v, w) in a.iter_mut().zip(words) {
                    *v = <$s>::read_words(core::slice::from_ref(w));
                }
                a.into()
            }
        }
    };
}

vector!(Vec2, f32, F32, 2, "Vec2", "vec2<f32>");
vector!(Vec3, f32, F32, 3, "Vec3", "vec3<f32>");
vector!(Vec4, f32, F32, 4, "Vec4", "vec4<f32>");
vector!(IVec2, i32, I32, 2, "IVec2", "vec2<i32>");
vector!(IVec3, i32, I32, 3, "IVec3", "vec3<i32>");
vector!(IVec4, i32, I32, 4, "IVec4", "vec4<i32>");
vector!(UVec2, u32, U32, 2, "UVec2", "vec2<u32>");
vector!(UVec3, u32, U32, 3, "UVec3", "vec3<u32>");
vector!(UVec4, u32, U32, 4, "UVec4", "vec4<u32>");

macro_rules! matrix {
    ($t:ty, $n:literal, $rust:literal, $wgsl:literal) => {
        impl RtData for $t {
            const LAYOUT: TypeLayout =
                TypeLayout { kind: LayoutKind::Matrix($n), rust: $rust, wgsl: $wgsl, words: $n * $n, fields: &[] };
            #[inline]
            fn write_words(&self, out: &mut [u32]) {
                let a = self.to_cols_array();
                match out.first_chunk_mut::<{ $n * $n }>() {
                    Some(o) => *o = a.map(f32::to_bits),
                    None => {
                        for (o, v) in out.iter_mut().zip(a) {
                            *o = v.to_bits();
                        }
                    }
                }
            }
            #[inline]
            fn read_words(words: &[u32]) -> Self {
                if let Some(w) = words.first_chunk::<{ $n * $n }>() {
                    return <$t>::from_cols_array(&w.map(f32::from_bits));
                }
                let mut a = [0.0f32; $n * $n];
                for (v, w) in a.iter_mut().zip(words) {
                    *v = f32::from_bits(*w);
                }
                <$t>::from_cols_array(&a)
            }
        }
    };
}

matrix!(Mat2, 2, "Mat2", "mat2x2<f32>");
matrix!(Mat3, 3, "Mat3", "mat3x3<f32>");
matrix!(Mat4, 4, "Mat4", "mat4x4<f32>");

// Tuples (struct fields of tuple types): the elements packed in order, as
// the WGSL struct `rt_tuple_<elements>_` the compiler declares for them.
// Their layout's names are generic: tuples are never variables or
// payloads, whose types the linker matches by name.
macro_rules! tuple {
    ($($t:ident $i:tt),+) => {
        impl<$($t: RtData),+> RtData for ($($t,)+) {
            const LAYOUT: TypeLayout =
            TypeLayout {
                kind: LayoutKind::Tuple,
                rust: "(tuple)",
                wgsl: "(tuple)",
                words: 0 $(+ $t::LAYOUT.words)+,
                fields: &[],
            };
            #[inline]
            #[allow(unused_assignments)]
            fn write_words(&self, out: &mut [u32]) {
                let mut at = 0usize;
                $(
                    self.$i.write_words(&mut out[at..]);
                    at += $t::LAYOUT.words as usize;
                )+
            }
            #[inline]
            #[allow(unused_assignments)]
            fn read_words(words: &[u32]) -> Self {
                let mut at = 0usize;
                ($(
                    {
                        let v = $t::read_words(&words[at..]);
                        at += $t::LAYOUT.words as usize;
                        v
                    },
                )+)
            }
        }
    };
}

tuple!(A 0);
tuple!(A 0, B 1);
tuple!(A 0, B 1, C 2);
tuple!(A 0, B 1, C 2, D 3);

/// Marker for types declared with `#[rt_payload]`: per-ray data.
#[diagnostic::on_unimplemented(message = "`{Self}` is not a ray payload", label = "mark `{Self}` with #[rt_payload]")]
pub trait Payload: RtData + Default {}

/// Marker for types declared with `#[rt_attributes]`: data an intersection
/// program hands to hit programs.
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not an attribute struct",
    label = "mark `{Self}` with #[rt_attributes]"
)]
pub trait Attributes: RtData + Default {
    /// Overwrites `self` with a triangle hit's built-in attributes, as the
    /// CPU backend hands them to closest-hit and any-hit programs: the fields
    /// `geometric_normal` and `shading_normal` (`Vec3`), `texcoord` and
    /// `barycentrics` (`Vec2`) receive them, every other field is zero
    /// ([`TriangleBuiltin`](crate::program::TriangleBuiltin)). The megakernel
    /// fills the same fields.
    ///
    /// `#[rt_attributes]` writes this field by field; this default goes
    /// through heap words.
    #[doc(hidden)]
    fn set_triangle(&mut self, t: &TriangleBuiltins) {
        self.read_words_into(&triangle_words(&Self::LAYOUT, t));
    }
}

/// The heap words of a value of layout `layout` holding a triangle hit's
/// built-in attributes ([`Attributes::set_triangle`]), found by the fields'
/// names and types.
#[doc(hidden)]
pub fn triangle_words(layout: &TypeLayout, t: &TriangleBuiltins) -> Vec<u32> {
    let mut words = vec![0u32; layout.words as usize];
    for f in layout.fields {
        let at = f.offset_words as usize;
        match TriangleBuiltin::of_field(f) {
            Some(TriangleBuiltin::GeometricNormal) => t.geometric_normal.write_words(&mut words[at..]),
            Some(TriangleBuiltin::ShadingNormal) => t.shading_normal.write_words(&mut words[at..]),
            Some(TriangleBuiltin::Texcoord) => t.texcoord.write_words(&mut words[at..]),
            Some(TriangleBuiltin::Barycentrics) => t.barycentrics.write_words(&mut words[at..]),
            None => {}
        }
    }
    words
}

// The checks `#[rt_program]` and `#[rt_function]` emit for the types they
// name (`rt_compiler::declared::declared_checks`): a type declared without
// its rt attribute gets one error that names the attribute to add. They
// go through traits of their own, with blanket impls rustc does not
// recommend, so the error lists no implementing types (a list that would
// change with every struct of the workspace). `DeclaredData` is the
// attributes' own (through `DeclaredByAttribute`), not every `RtData`'s:
// a type alias of a glam type without `#[rt_type]` is refused by it too,
// and told why (an `#[rt_type]` alias is not asked: see
// `rt_compiler::declared`).
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "this type is not declared for ray programs",
    label = "`{Self}` is not declared with #[rt_struct], #[rt_payload], #[rt_attributes] or #[rt_enum]",
    note = "a type of your own needs the attribute on its declaration, and a `type` alias of `{Self}` needs #[rt_type] on its own"
)]
pub trait DeclaredData {}
#[diagnostic::do_not_recommend]
impl<T: DeclaredByAttribute> DeclaredData for T {}

/// Implemented by `#[rt_struct]`, `#[rt_payload]`, `#[rt_attributes]` and
/// `#[rt_enum]` for their type.
#[doc(hidden)]
pub trait DeclaredByAttribute {}

#[doc(hidden)]
#[diagnostic::on_unimplemented(message = "`{Self}` is not a ray payload", label = "mark `{Self}` with #[rt_payload]")]
pub trait DeclaredPayload {}
#[diagnostic::do_not_recommend]
impl<T: Payload> DeclaredPayload for T {}

#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`{Self}` is not an attribute struct",
    label = "mark `{Self}` with #[rt_attributes]"
)]
pub trait DeclaredAttributes {}
#[diagnostic::do_not_recommend]
impl<T: Attributes> DeclaredAttributes for T {}

/// The default of every type parameter of a generic `#[rt_struct]`, so that
/// the check that a program's types were declared (`__require_declared`)
/// may name the struct without its arguments, as a program may
/// (`Pair::new(..)`, `Pair { .. }`); programs never name it.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct __RtAnyType;

/// Requires that `T` was declared with an rt attribute.
#[doc(hidden)]
#[inline(always)]
pub fn __require_declared<T: DeclaredData + ?Sized>() {}

/// Requires that `T` was declared with `#[rt_payload]`.
#[doc(hidden)]
#[inline(always)]
pub fn __require_payload<T: DeclaredPayload + ?Sized>() {}

/// Requires that `T` was declared with `#[rt_attributes]`.
#[doc(hidden)]
#[inline(always)]
pub fn __require_attributes<T: DeclaredAttributes + ?Sized>() {}

/// Implemented by `#[rt_impl]` for its type: `#[rt_struct(impl)]` requires
/// it, so a struct that says it has an impl block and has none is told so.
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`{Self}` is declared with `(impl)` but has no #[rt_impl] block",
    label = "write `#[rt_impl] impl {Self} {{ .. }}` beside it, or drop `(impl)`"
)]
pub trait __RtImplBlock {}
#[diagnostic::do_not_recommend]
impl<T: __HasRtImplBlock + ?Sized> __RtImplBlock for T {}

/// What `#[rt_impl]` implements; `__RtImplBlock` is asked of it through a
/// blanket impl, so an error lists no implementing types (that list would
/// change with every impl in the workspace).
#[doc(hidden)]
pub trait __HasRtImplBlock {}

/// Implemented by `#[rt_struct(impl)]` (and `#[rt_payload(impl)]`,
/// `#[rt_attributes(impl)]`): `#[rt_impl]` requires it, because the
/// struct's link in the macro chain is what carries the impl to programs.
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "`{Self}` has an #[rt_impl] block, but its declaration does not say so",
    label = "declare `{Self}` with #[rt_struct(impl)] (or #[rt_payload(impl)], #[rt_attributes(impl)])"
)]
pub trait __RtImplDeclared {}
#[diagnostic::do_not_recommend]
impl<T: __DeclaresRtImpl + ?Sized> __RtImplDeclared for T {}

/// What `#[rt_struct(impl)]` implements (see `__HasRtImplBlock`).
#[doc(hidden)]
pub trait __DeclaresRtImpl {}

/// Requires that `T` has an `#[rt_impl]` block.
#[doc(hidden)]
#[inline(always)]
pub fn __require_impl_block<T: __RtImplBlock + ?Sized>() {}

/// Requires that `T` was declared with `(impl)`.
#[doc(hidden)]
#[inline(always)]
pub fn __require_impl_declared<T: __RtImplDeclared + ?Sized>() {}

/// Asked of the name of a constant a program names: `#[rt_const]`
/// declares a marker of that name implementing it (see
/// `rt_compiler::declared`); a plain `const` has none (one of the item's
/// own module is taken without it: `rt_compiler::plain_consts`).
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "this constant is not declared for ray programs",
    label = "declare it with #[rt_const]: the macros that compile programs see a plain `const` only in the module of the item that names it"
)]
pub trait __RtConstDeclared {}
#[diagnostic::do_not_recommend]
impl<T: __RtConstMarker + ?Sized> __RtConstDeclared for T {}

/// What `#[rt_const]` implements for its marker.
#[doc(hidden)]
pub trait __RtConstMarker {}

/// Asked of the name of a function a program calls: `#[rt_function]`
/// declares a marker of that name implementing it; a plain `fn` has none.
#[doc(hidden)]
#[diagnostic::on_unimplemented(
    message = "this function is not declared for ray programs",
    label = "declare it with #[rt_function]: a plain `fn` is not seen by the macros that compile programs"
)]
pub trait __RtFunctionDeclared {}
#[diagnostic::do_not_recommend]
impl<T: __RtFunctionMarker + ?Sized> __RtFunctionDeclared for T {}

/// What `#[rt_function]` implements for its marker.
#[doc(hidden)]
pub trait __RtFunctionMarker {}

/// Requires that the constant of this name was declared with `#[rt_const]`.
#[doc(hidden)]
#[inline(always)]
pub fn __require_rt_const<T: __RtConstDeclared + ?Sized>() {}

/// Requires that the function of this name was declared with
/// `#[rt_function]`.
#[doc(hidden)]
#[inline(always)]
pub fn __require_rt_function<T: __RtFunctionDeclared + ?Sized>() {}

/// The value of `T` whose words are all zero (what out-of-bounds loads read,
/// and the fields of attributes no triangle hit fills).
#[doc(hidden)]
pub fn zeroed<T: RtData>() -> T {
    static ZEROS: [u32; 1024] = [0; 1024];
    let words = T::LAYOUT.words as usize;
    if words <= ZEROS.len() { T::read_words(&ZEROS[..words]) } else { T::read_words(&vec![0; words]) }
}
