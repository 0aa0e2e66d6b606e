//! The type model of the subset: what a value can be, how it is spelled in
//! Rust and WGSL, and its packed layout in the runtime's heap (one 32-bit
//! word per scalar, fields in declaration order, no padding). This file is
//! the one place that knows a type's WGSL spelling and layout.

use std::fmt;
use std::rc::Rc;

/// A scalar type. `usize` exists only because Rust indexes arrays with it;
/// it is a `u32` in WGSL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Scalar {
    F32,
    I32,
    U32,
    Usize,
    Bool,
}

impl Scalar {
    pub fn rust(self) -> &'static str {
        match self {
            Scalar::F32 => "f32",
            Scalar::I32 => "i32",
            Scalar::U32 => "u32",
            Scalar::Usize => "usize",
            Scalar::Bool => "bool",
        }
    }

    pub fn wgsl(self) -> &'static str {
        match self {
            Scalar::F32 => "f32",
            Scalar::I32 => "i32",
            Scalar::U32 | Scalar::Usize => "u32",
            Scalar::Bool => "bool",
        }
    }

    pub fn is_int(self) -> bool {
        matches!(self, Scalar::I32 | Scalar::U32 | Scalar::Usize)
    }

    pub fn is_numeric(self) -> bool {
        self != Scalar::Bool
    }

    /// glam's prefix for vectors of this scalar (`Vec3`, `IVec3`, `UVec3`).
    fn glam_prefix(self) -> &'static str {
        match self {
            Scalar::F32 => "",
            Scalar::I32 => "I",
            Scalar::U32 | Scalar::Usize => "U",
            Scalar::Bool => "B",
        }
    }
}

/// Which buffer handle type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BufferKind {
    pub dims: u8,
    pub writable: bool,
}

impl BufferKind {
    pub fn rust_name(self) -> &'static str {
        match (self.dims, self.writable) {
            (1, false) => "Buffer",
            (1, true) => "RwBuffer",
            (2, false) => "Buffer2d",
            (2, true) => "RwBuffer2d",
            (_, false) => "Buffer3d",
            (_, true) => "RwBuffer3d",
        }
    }

    /// The type of its indices: `u32`, `UVec2` or `UVec3`.
    pub fn index_ty(self) -> Ty {
        match self.dims {
            1 => Ty::Scalar(Scalar::U32),
            d => Ty::Vec(d, Scalar::U32),
        }
    }
}

/// A user struct declared with `#[rt_struct]`, `#[rt_payload]` or
/// `#[rt_attributes]`.
#[derive(Debug)]
pub struct StructDef {
    pub name: String,
    pub wgsl_name: String,
    pub role: crate::StructRole,
    pub fields: Vec<(String, Ty)>,
    pub span: proc_macro2::Span,
    /// An instance of a generic struct: the struct's name and the
    /// arguments (see `lower::generic_structs`).
    pub generic: Option<(String, Vec<Ty>)>,
}

impl StructDef {
    /// The first instance of a generic struct this struct is or holds.
    fn generic_instance(self: &Rc<Self>) -> Option<&Rc<StructDef>> {
        if self.generic.is_some() {
            return Some(self);
        }
        self.fields.iter().find_map(|(_, t)| t.generic_instance())
    }

    /// The name its `#[rt_impl]` block is keyed by: an instance's generic
    /// struct's (`Pair` for `Pair<f32>`), else its own.
    pub fn impl_name(&self) -> &str {
        self.generic.as_ref().map_or(&self.name, |(g, _)| g)
    }

    pub fn field(&self, name: &str) -> Option<&Ty> {
        self.fields.iter().find(|(n, _)| n == name).map(|(_, t)| t)
    }

    /// Whether it is a tuple struct (`struct Rgb(f32, f32, f32);`): its
    /// fields are named `0`, `1`, ...
    pub fn is_tuple(&self) -> bool {
        self.fields.first().is_some_and(|(n, _)| n == "0")
    }
}

/// A C-like enum declared with `#[rt_enum]`: a `u32` in WGSL and one word
/// in the heap, its variants' discriminants as values.
#[derive(Debug)]
pub struct EnumDef {
    pub name: String,
    /// `(variant, discriminant)` in declaration order.
    pub variants: Vec<(String, u32)>,
    pub span: proc_macro2::Span,
}

impl EnumDef {
    pub fn variant(&self, name: &str) -> Option<u32> {
        self.variants.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }
}

/// The signature of a callable program or of a [`Ty::Callable`] id.
#[derive(Clone, Debug, PartialEq)]
pub struct CallSig {
    pub params: Vec<Ty>,
    pub ret: Ty,
}

impl CallSig {
    /// `fn(Vec3, Vec3) -> Vec3`, `fn(u32)`: as the descriptors and messages
    /// spell it.
    pub fn rust(&self) -> String {
        let params: Vec<String> = self.params.iter().map(Ty::to_string).collect();
        match self.ret {
            Ty::Unit => format!("fn({})", params.join(", ")),
            ref r => format!("fn({}) -> {r}", params.join(", ")),
        }
    }

    /// The WGSL dispatch function of the signature,
    /// `rt_call_<parameters>__<result>_`: one per signature in a megakernel.
    pub fn dispatch(&self) -> String {
        let key = |t: &Ty| match t {
            // Enums and ids are `u32`s in WGSL; their names keep the
            // signatures apart.
            Ty::Enum(e) => format!("e{}", e.name),
            Ty::Callable(c) => format!("c{}", c.dispatch()),
            Ty::BufferId(w, e) => format!("b{}{}", if *w { "w" } else { "" }, e.mangle()),
            Ty::SamplerId(s) => format!("t{s}"),
            Ty::Unit => "void".into(),
            t => t.mangle(),
        };
        let params: Vec<String> = self.params.iter().map(key).collect();
        format!("rt_call_{}__{}_", params.join("_"), key(&self.ret))
    }
}

/// A type in the subset.
#[derive(Clone, Debug)]
pub enum Ty {
    Unit,
    Scalar(Scalar),
    /// An integer whose type is not yet known (an unsuffixed literal);
    /// resolved by unification, i32 by default as in Rust.
    IntVar(u32),
    Vec(u8, Scalar),
    /// Square f32 matrix (`Mat2`, `Mat3`, `Mat4`).
    Mat(u8),
    Struct(Rc<StructDef>),
    /// A `#[rt_enum]`.
    Enum(Rc<EnumDef>),
    /// `Callable<fn(A, ..) -> R>`: the id of a callable program, a `u32`.
    Callable(Rc<CallSig>),
    /// `BindlessBuffer<T>` (`RwBindlessBuffer<T>` when `true`): the id of a
    /// buffer of `T`, a `u32`.
    BufferId(bool, Box<Ty>),
    /// `BindlessSampler<S>`: the id of a sampler of shape `S` (`Sampler`,
    /// `Sampler3d` or `SamplerCube`), a `u32`.
    SamplerId(Box<Ty>),
    /// `(A, B, ...)`, at least one element: a WGSL struct with fields `f0`,
    /// `f1`, ... (see [`Ty::wgsl`]).
    Tuple(Vec<Ty>),
    /// `Option<T>`: a WGSL struct of a flag and a value, `some` and
    /// `value` (the value's zero when `None`); never stored where the host
    /// reads (see [`Ty::is_plain_data`]).
    Option(Box<Ty>),
    Array(Box<Ty>, u32),
    Ray,
    Aabb,
    Object,
    TransformKind,
    Buffer(BufferKind, Box<Ty>),
    Sampler,
    Sampler3d,
    /// A cube map: WGSL `RtSampler` (six square faces), 4 words.
    SamplerCube,
    /// `&T` / `&mut T`: only parameters and arguments.
    Ref(bool, Box<Ty>),
    /// The type of `return`, `break`, `continue`.
    Never,
}

impl PartialEq for Ty {
    fn eq(&self, other: &Ty) -> bool {
        use Ty::*;
        match (self, other) {
            (Unit, Unit) | (Ray, Ray) | (Aabb, Aabb) | (Object, Object) | (Sampler, Sampler) => true,
            (Sampler3d, Sampler3d) | (SamplerCube, SamplerCube) => true,
            (TransformKind, TransformKind) | (Never, Never) => true,
            (Scalar(a), Scalar(b)) => a == b,
            (IntVar(a), IntVar(b)) => a == b,
            (Vec(n, a), Vec(m, b)) => n == m && a == b,
            (Mat(n), Mat(m)) => n == m,
            (Struct(a), Struct(b)) => a.name == b.name,
            (Enum(a), Enum(b)) => a.name == b.name,
            (Callable(a), Callable(b)) => a == b,
            (BufferId(v, a), BufferId(w, b)) => v == w && a == b,
            (SamplerId(a), SamplerId(b)) => a == b,
            (Tuple(a), Tuple(b)) => a == b,
            (Option(a), Option(b)) => a == b,
            (Array(a, n), Array(b, m)) => n == m && a == b,
            (Buffer(k, a), Buffer(l, b)) => k == l && a == b,
            (Ref(m, a), Ref(n, b)) => m == n && a == b,
            _ => false,
        }
    }
}

pub const F32: Ty = Ty::Scalar(Scalar::F32);
pub const I32: Ty = Ty::Scalar(Scalar::I32);
pub const U32: Ty = Ty::Scalar(Scalar::U32);
pub const BOOL: Ty = Ty::Scalar(Scalar::Bool);

impl Ty {
    pub fn vec(n: u8) -> Ty {
        Ty::Vec(n, Scalar::F32)
    }

    /// The scalar of a scalar or vector type.
    pub fn scalar(&self) -> Option<Scalar> {
        match self {
            Ty::Scalar(s) | Ty::Vec(_, s) => Some(*s),
            Ty::Mat(_) => Some(Scalar::F32),
            _ => None,
        }
    }

    pub fn is_value(&self) -> bool {
        !matches!(self, Ty::Unit | Ty::Never | Ty::Ref(..))
    }

    /// Whether values of this type may be stored in buffers, variables and
    /// structs (handles may be variables, but not buffer elements).
    pub fn is_plain_data(&self) -> bool {
        match self {
            Ty::Scalar(s) => *s != Scalar::Usize,
            Ty::Vec(_, s) => *s != Scalar::Bool,
            Ty::Mat(_) | Ty::Struct(_) | Ty::Enum(_) | Ty::Callable(_) | Ty::BufferId(..) | Ty::SamplerId(_) => true,
            Ty::Ray | Ty::Aabb => true,
            Ty::Array(t, _) => t.is_plain_data(),
            Ty::Tuple(ts) => ts.iter().all(Ty::is_plain_data),
            _ => false,
        }
    }

    /// Whether WGSL spells this type `u32` though it is no integer to the
    /// program: a node handle, a transform kind, an enum, a callable id, a
    /// bindless buffer or sampler id. One heap word, compared with `==`,
    /// loaded and stored as the word itself.
    pub fn is_u32_word(&self) -> bool {
        matches!(
            self,
            Ty::Object | Ty::TransformKind | Ty::Enum(_) | Ty::Callable(_) | Ty::BufferId(..) | Ty::SamplerId(_)
        )
    }

    /// The Rust name of the type as its `RtData` layout spells it (rt-std's
    /// `TypeLayout::rust`), whose `rt_abi::records::layout_tag` the runtime
    /// writes for each buffer: ids share one layout whatever they name.
    pub fn layout_name(&self) -> String {
        match self {
            Ty::Callable(_) => "Callable".into(),
            Ty::BufferId(false, _) => "BindlessBuffer".into(),
            Ty::BufferId(true, _) => "RwBindlessBuffer".into(),
            Ty::SamplerId(_) => BINDLESS_SAMPLER.into(),
            t => t.to_string(),
        }
    }

    /// Rust spelling, for messages and descriptors.
    pub fn rust(&self) -> String {
        self.to_string()
    }

    /// WGSL spelling. Unresolved integer variables are spelled as a
    /// placeholder the final pass of `lower` resolves.
    pub fn wgsl(&self) -> String {
        match self {
            Ty::Unit | Ty::Never => "void".into(),
            Ty::Scalar(s) => s.wgsl().into(),
            Ty::IntVar(v) => crate::lower::text::int_type_placeholder(*v),
            Ty::Vec(n, s) => format!("vec{n}<{}>", s.wgsl()),
            Ty::Mat(n) => format!("mat{n}x{n}<f32>"),
            Ty::Struct(s) => s.wgsl_name.clone(),
            Ty::Array(t, n) => format!("array<{}, {n}>", t.wgsl()),
            // One name per element list, the same in every module (the
            // linker shares it); `rt_` names are never the user's, and the
            // trailing `_` keeps naga from renaming it.
            Ty::Tuple(ts) => format!("rt_tuple_{}_", ts.iter().map(Ty::mangle).collect::<Vec<_>>().join("_")),
            Ty::Option(t) => format!("rt_option_{}_", t.mangle()),
            Ty::Ray => "RtRay".into(),
            Ty::Aabb => "RtAabb".into(),
            Ty::Object | Ty::TransformKind | Ty::Enum(_) | Ty::Callable(_) | Ty::BufferId(..) | Ty::SamplerId(_) => {
                "u32".into()
            }
            Ty::Buffer(..) => "RtBuffer".into(),
            Ty::Sampler | Ty::SamplerCube => "RtSampler".into(),
            Ty::Sampler3d => "RtSampler3d".into(),
            Ty::Ref(true, t) => format!("ptr<function, {}>", t.wgsl()),
            Ty::Ref(false, t) => t.wgsl(),
        }
    }

    /// A WGSL-identifier-safe name for the type, for generated accessors
    /// (`rt_load_vec3f`, `rt_load_Radiance`).
    /// The first instance of a generic struct (`lower::generic_structs`)
    /// the type is, holds or names: a value of it never reaches the host.
    pub fn generic_instance(&self) -> Option<&Rc<StructDef>> {
        match self {
            Ty::Struct(d) => d.generic_instance(),
            Ty::Array(t, _) | Ty::Ref(_, t) | Ty::Option(t) | Ty::Buffer(_, t) | Ty::BufferId(_, t) => {
                t.generic_instance()
            }
            Ty::Tuple(ts) => ts.iter().find_map(Ty::generic_instance),
            Ty::Callable(sig) => sig.params.iter().chain(std::iter::once(&sig.ret)).find_map(Ty::generic_instance),
            _ => None,
        }
    }

    pub fn mangle(&self) -> String {
        match self {
            Ty::Scalar(s) => s.wgsl().into(),
            Ty::Vec(n, s) => format!("vec{n}{}", &s.wgsl()[..1]),
            Ty::Mat(n) => format!("mat{n}"),
            Ty::Struct(s) => s.wgsl_name.clone(),
            Ty::Array(t, n) => format!("arr{n}_{}", t.mangle()),
            Ty::Ray => "RtRay".into(),
            Ty::Aabb => "RtAabb".into(),
            other => other.wgsl(),
        }
    }

    /// Size in 32-bit words when stored in the heap.
    pub fn words(&self) -> u32 {
        match self {
            Ty::Scalar(_) | Ty::IntVar(_) => 1,
            Ty::Object | Ty::TransformKind | Ty::Enum(_) | Ty::Callable(_) | Ty::BufferId(..) | Ty::SamplerId(_) => 1,
            Ty::Vec(n, _) => *n as u32,
            Ty::Mat(n) => (*n as u32) * (*n as u32),
            Ty::Struct(s) => s.fields.iter().map(|(_, t)| t.words()).sum(),
            Ty::Array(t, n) => t.words() * n,
            Ty::Tuple(ts) => ts.iter().map(Ty::words).sum(),
            Ty::Option(t) => 1 + t.words(),
            Ty::Ray => 9,
            Ty::Aabb => 6,
            Ty::Buffer(..) | Ty::Sampler | Ty::SamplerCube => 4,
            Ty::Sampler3d => 5,
            Ty::Unit | Ty::Never | Ty::Ref(..) => 0,
        }
    }

    /// Fields of a struct-like type, with types.
    pub fn fields(&self) -> Vec<(String, Ty)> {
        match self {
            Ty::Struct(s) => s.fields.clone(),
            Ty::Ray => vec![
                ("origin".into(), Ty::vec(3)),
                ("direction".into(), Ty::vec(3)),
                ("ray_type".into(), U32),
                ("tmin".into(), F32),
                ("tmax".into(), F32),
            ],
            Ty::Aabb => vec![("min".into(), Ty::vec(3)), ("max".into(), Ty::vec(3))],
            Ty::Tuple(ts) => ts.iter().enumerate().map(|(i, t)| (format!("f{i}"), t.clone())).collect(),
            Ty::Option(t) => vec![("some".into(), BOOL), ("value".into(), (**t).clone())],
            _ => Vec::new(),
        }
    }
}

impl fmt::Display for Ty {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Ty::Unit => write!(f, "()"),
            Ty::Never => write!(f, "!"),
            Ty::Scalar(s) => write!(f, "{}", s.rust()),
            Ty::IntVar(_) => write!(f, "{{integer}}"),
            Ty::Vec(n, s) => write!(f, "{}Vec{n}", s.glam_prefix()),
            Ty::Mat(n) => write!(f, "Mat{n}"),
            Ty::Struct(s) => write!(f, "{}", s.name),
            Ty::Enum(e) => write!(f, "{}", e.name),
            Ty::Callable(c) => write!(f, "Callable<{}>", c.rust()),
            Ty::BufferId(w, t) => write!(f, "{}<{t}>", bindless_name(*w)),
            Ty::SamplerId(t) => write!(f, "{BINDLESS_SAMPLER}<{t}>"),
            Ty::Tuple(ts) => {
                let parts: Vec<String> = ts.iter().map(Ty::to_string).collect();
                if parts.len() == 1 { write!(f, "({},)", parts[0]) } else { write!(f, "({})", parts.join(", ")) }
            }
            Ty::Option(t) => write!(f, "Option<{t}>"),
            Ty::Array(t, n) => write!(f, "[{t}; {n}]"),
            Ty::Ray => write!(f, "Ray"),
            Ty::Aabb => write!(f, "Aabb"),
            Ty::Object => write!(f, "Object"),
            Ty::TransformKind => write!(f, "TransformKind"),
            Ty::Buffer(k, t) => write!(f, "{}<{t}>", k.rust_name()),
            Ty::Sampler => write!(f, "Sampler2d"),
            Ty::Sampler3d => write!(f, "Sampler3d"),
            Ty::SamplerCube => write!(f, "SamplerCube"),
            Ty::Ref(true, t) => write!(f, "&mut {t}"),
            Ty::Ref(false, t) => write!(f, "&{t}"),
        }
    }
}

/// Parses a glam/scalar type name (last path segment) into a type.
pub fn builtin_type(name: &str) -> Option<Ty> {
    Some(match name {
        "f32" => F32,
        "i32" => I32,
        "u32" => U32,
        "usize" => Ty::Scalar(Scalar::Usize),
        "bool" => BOOL,
        "Vec2" => Ty::Vec(2, Scalar::F32),
        "Vec3" => Ty::Vec(3, Scalar::F32),
        "Vec4" => Ty::Vec(4, Scalar::F32),
        "IVec2" => Ty::Vec(2, Scalar::I32),
        "IVec3" => Ty::Vec(3, Scalar::I32),
        "IVec4" => Ty::Vec(4, Scalar::I32),
        "UVec2" => Ty::Vec(2, Scalar::U32),
        "UVec3" => Ty::Vec(3, Scalar::U32),
        "UVec4" => Ty::Vec(4, Scalar::U32),
        // `BVec4A` is what `Vec4`'s comparisons return where glam's `Vec4`
        // is SIMD (x86_64, aarch64, wasm32): in WGSL a `vec4<bool>` alike.
        "BVec2" => Ty::Vec(2, Scalar::Bool),
        "BVec3" => Ty::Vec(3, Scalar::Bool),
        "BVec4" | "BVec4A" => Ty::Vec(4, Scalar::Bool),
        "Mat2" => Ty::Mat(2),
        "Mat3" => Ty::Mat(3),
        "Mat4" => Ty::Mat(4),
        "Ray" => Ty::Ray,
        "Aabb" => Ty::Aabb,
        "Object" => Ty::Object,
        "TransformKind" => Ty::TransformKind,
        "Sampler2d" => Ty::Sampler,
        "Sampler3d" => Ty::Sampler3d,
        "SamplerCube" => Ty::SamplerCube,
        _ => return None,
    })
}

/// The type name of a bindless sampler id, `BindlessSampler<S>`.
pub const BINDLESS_SAMPLER: &str = "BindlessSampler";

/// The type name of a bindless buffer id, read-only or writable.
pub fn bindless_name(writable: bool) -> &'static str {
    if writable { "RwBindlessBuffer" } else { "BindlessBuffer" }
}

/// Whether `name` is a bindless buffer id's type name, and if so whether
/// writable.
pub fn bindless_kind(name: &str) -> Option<bool> {
    match name {
        "BindlessBuffer" => Some(false),
        "RwBindlessBuffer" => Some(true),
        _ => None,
    }
}

/// Buffer handle type names.
pub fn buffer_kind(name: &str) -> Option<BufferKind> {
    Some(match name {
        "Buffer" => BufferKind { dims: 1, writable: false },
        "RwBuffer" => BufferKind { dims: 1, writable: true },
        "Buffer2d" => BufferKind { dims: 2, writable: false },
        "RwBuffer2d" => BufferKind { dims: 2, writable: true },
        "Buffer3d" => BufferKind { dims: 3, writable: false },
        "RwBuffer3d" => BufferKind { dims: 3, writable: true },
        _ => return None,
    })
}

/// The scalar types the subset refuses, each with its advice in
/// [`unsupported_type_advice`]: `rt_std::arith` implements nothing for
/// them, so the CPU copy of a function naming one is left as written
/// (`cpu_semantics`).
pub const REFUSED_SCALARS: &[&str] = &["f64", "i64", "u64", "i128", "u128", "isize", "i8", "u8", "i16", "u16"];

/// Type names that Rust users reach for but the subset rejects, with what to
/// use instead (the message reads "the type `T` is not supported in ray
/// programs: `<advice>`").
pub fn unsupported_type_advice(name: &str) -> Option<&'static str> {
    Some(match name {
        "f64" => "the GPU computes in f32; use f32",
        "i64" | "u64" | "i128" | "u128" | "isize" => "integers are 32-bit; use i32 or u32",
        "i8" | "u8" | "i16" | "u16" => "integers are 32-bit; use i32 or u32 (and mask bits)",
        "String" | "str" => "programs have no strings; use numbers (ids, codes), and `rt_printf!` to print",
        "Vec" | "VecDeque" | "HashMap" | "BTreeMap" | "Box" | "Rc" | "Arc" => {
            "programs have no heap; use a fixed-size array or a buffer variable"
        }
        "Result" => "return an `Option`, or a flag or a sentinel value",
        "DVec2" | "DVec3" | "DVec4" | "DMat3" | "DMat4" => "the GPU computes in f32; use Vec2/Vec3/Vec4 and Mat3/Mat4",
        "Vec3A" => "use Vec3",
        "Quat" => "use Mat3/Mat4",
        _ => return None,
    })
}
