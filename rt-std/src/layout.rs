//! How values are laid out where the CPU and the GPU share them: a type's
//! layout in the runtime's heap words and its spellings, a struct's
//! fields, and the built-in attributes of a triangle hit. The bottom of
//! the crate: it names no other module of it, so every other module may
//! name it.

/// One field of a struct type, in packed 32-bit words.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FieldLayout {
    /// Field name.
    pub name: &'static str,
    /// Rust spelling of the field's type (for messages).
    pub ty: &'static str,
    /// What kind of type the field is.
    pub kind: LayoutKind,
    /// Offset in 32-bit words from the start of the struct.
    pub offset_words: u32,
}

/// A built-in attribute of a triangle hit, which the fields of an attribute
/// struct receive by name and type: `geometric_normal` and `shading_normal`
/// of type `Vec3`, `texcoord` and `barycentrics` of type `Vec2` (spelled as
/// a path too, `glam::Vec2`). Every backend fills them by this rule.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TriangleBuiltin {
    GeometricNormal,
    ShadingNormal,
    Texcoord,
    Barycentrics,
}

impl TriangleBuiltin {
    /// The built-in a field of this name and type (as the layout spells
    /// it) receives, if any. `#[rt_attributes]` applies the same rule when
    /// it generates `Attributes::set_triangle` (rt-compiler's `expand/data.rs`,
    /// which cannot call this).
    pub fn of_field(f: &FieldLayout) -> Option<Self> {
        const VEC2: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 2 };
        const VEC3: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 3 };
        match (f.name, f.kind) {
            ("geometric_normal", VEC3) => Some(Self::GeometricNormal),
            ("shading_normal", VEC3) => Some(Self::ShadingNormal),
            ("texcoord", VEC2) => Some(Self::Texcoord),
            ("barycentrics", VEC2) => Some(Self::Barycentrics),
            _ => None,
        }
    }
}

/// A 32-bit scalar of the heap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScalarKind {
    /// `f32`.
    F32,
    /// `i32`.
    I32,
    /// `u32`.
    U32,
    /// `bool`, one word.
    Bool,
}

/// The shape of a sampler a `BindlessSampler<S>` id names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SamplerKind {
    /// `Sampler2d`.
    Flat,
    /// `Sampler3d`.
    Volume,
    /// `SamplerCube`.
    Cube,
}

/// What kind of type a [`TypeLayout`] describes, so that the runtime
/// matches types by their structure and never reads their Rust spelling.
///
/// The ids' kinds carry what they name where the layout's maker knows it:
/// the compiler always does (a program's variable of type
/// `BindlessBuffer<Vec3>` is `BufferId { element: Some(Vec3's layout) }`);
/// a host value of a generic id type may not (`Callable<F>` is
/// `Callable(None)`), and the linker then checks the id against what it
/// names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutKind {
    /// `()`: no words.
    Unit,
    /// One scalar.
    Scalar(ScalarKind),
    /// A glam vector of `len` scalars.
    Vector {
        /// Its scalar.
        scalar: ScalarKind,
        /// 2, 3 or 4.
        len: u8,
    },
    /// A square f32 matrix of this size, column-major.
    Matrix(u8),
    /// A `#[rt_struct]`, `#[rt_payload]` or `#[rt_attributes]` struct.
    Struct,
    /// A `#[rt_enum]`: one word.
    Enum,
    /// A tuple.
    Tuple,
    /// A fixed array of `len` elements.
    Array(u32),
    /// A buffer, sampler or node a variable is bound to (the variable's
    /// `VariableKind` says which).
    Handle,
    /// A struct the runtime defines (`Ray`, `Aabb`).
    Builtin,
    /// `Callable<fn(..) -> R>`: a callable program's id, with its signature.
    Callable(Option<&'static CallableSignature>),
    /// `BindlessBuffer<T>` (`writable`: `RwBindlessBuffer<T>`): a buffer's
    /// id, with the layout of `T`.
    BufferId {
        /// Programs may write through the id.
        writable: bool,
        /// The element's layout.
        element: Option<&'static TypeLayout>,
    },
    /// `BindlessSampler<S>`: a sampler's id, with the shape `S`.
    SamplerId(Option<SamplerKind>),
}

/// How a type is spelled in Rust and WGSL, and how it is laid out in the
/// runtime's buffer heap: fields packed in declaration order, four bytes per
/// scalar, no padding (so the same bytes serve CPU and GPU).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TypeLayout {
    /// What kind of type it is, and what an id names.
    pub kind: LayoutKind,
    /// The Rust spelling (`Vec3`, `Radiance`, `Buffer<BasicLight>`).
    pub rust: &'static str,
    /// The WGSL spelling (`vec3<f32>`, `Radiance`, `RtBuffer`).
    pub wgsl: &'static str,
    /// Size in 32-bit words when stored in a buffer.
    pub words: u32,
    /// Fields, for struct types; empty otherwise.
    pub fields: &'static [FieldLayout],
}

/// The built-in attributes of a triangle hit, which attribute structs
/// receive in their fields of the same names and types.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TriangleBuiltins {
    /// The triangle's unnormalised normal, `(b - a) x (c - a)`.
    pub geometric_normal: glam::Vec3,
    /// The vertex normals interpolated at the hit (the geometric normal when
    /// the mesh has none).
    pub shading_normal: glam::Vec3,
    /// The texture coordinates interpolated at the hit (the barycentrics
    /// when the mesh has none).
    pub texcoord: glam::Vec2,
    /// The weights of vertices `b` and `c`.
    pub barycentrics: glam::Vec2,
}

/// The signature of a callable program, or of a call through a
/// `Callable` id: the megakernel has one dispatch
/// function per signature, `switch`ing over the callables of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CallableSignature {
    /// The Rust spelling, `fn(Vec3, Vec3) -> Vec3` (`fn(u32)` for no result).
    pub rust: &'static str,
    /// The WGSL dispatch function a call lowers to,
    /// `rt_call_<parameters>__<result>`.
    pub dispatch: &'static str,
    /// The WGSL parameter types, in order.
    pub params: &'static [&'static str],
    /// The WGSL result type; `None` for no result.
    pub ret: Option<&'static str>,
}
