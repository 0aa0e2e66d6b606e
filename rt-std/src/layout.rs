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
    /// Rust spelling of the field's type.
    pub ty: &'static str,
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
        let ty = f.ty.rsplit("::").next().unwrap_or(f.ty).trim();
        match (f.name, ty) {
            ("geometric_normal", "Vec3") => Some(Self::GeometricNormal),
            ("shading_normal", "Vec3") => Some(Self::ShadingNormal),
            ("texcoord", "Vec2") => Some(Self::Texcoord),
            ("barycentrics", "Vec2") => Some(Self::Barycentrics),
            _ => None,
        }
    }
}

/// How a type is spelled in Rust and WGSL, and how it is laid out in the
/// runtime's buffer heap: fields packed in declaration order, four bytes per
/// scalar, no padding (so the same bytes serve CPU and GPU).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TypeLayout {
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
