//! Variables and scopes.
//!
//! A program reads the variables its signature declares (`#[var] name: T`).
//! Their values are set by name on scopes — the context, a program, a
//! geometry, a geometry instance, a material, a node — and each program kind
//! looks them up in OptiX's order, innermost first, inner scopes shadowing
//! outer ones ([`lookup_order`]). Resolution happens once per link, per
//! program and scope record, never per ray.

use crate::handles::{BufferId, NodeId, SamplerId};
use rt_std::RtData;
use rt_std::program::{ProgramKind, TypeLayout};
use std::any::Any;
use std::collections::BTreeMap;
use std::sync::Arc;

/// A scope kind, in lookup terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScopeKind {
    /// Variables of the program itself.
    Program,
    /// Variables of the geometry instance hit (or intersected).
    GeometryInstance,
    /// Variables of the material hit.
    Material,
    /// Variables of the geometry intersected.
    Geometry,
    /// Variables of the node a selector visits.
    Node,
    /// Variables of the context.
    Context,
}

/// OptiX's lookup order for a program kind, innermost first.
pub fn lookup_order(kind: ProgramKind) -> &'static [ScopeKind] {
    use ScopeKind::*;
    match kind {
        ProgramKind::RayGeneration | ProgramKind::Exception | ProgramKind::Miss => &[Program, Context],
        ProgramKind::ClosestHit | ProgramKind::AnyHit => &[Program, GeometryInstance, Material, Context],
        ProgramKind::Intersection | ProgramKind::BoundingBox => &[Program, GeometryInstance, Geometry, Context],
        ProgramKind::Visit => &[Program, Node],
        // OptiX's bindless callables: their program, then the context.
        ProgramKind::Callable => &[Program, Context],
    }
}

/// A variable's value.
#[derive(Clone)]
pub enum VarValue {
    /// Plain data: its layout, its heap words (GPU) and the Rust value (CPU).
    Data {
        /// The type: its Rust and WGSL spellings and its size in words.
        layout: TypeLayout,
        /// The value as the GPU heap holds it.
        words: Vec<u32>,
        /// The value itself, for the CPU backend.
        value: Arc<dyn Any + Send + Sync>,
    },
    /// A buffer (a program's `Buffer`, `RwBuffer` and their 2D and 3D kinds).
    Buffer(BufferId),
    /// A texture sampler (a program's `Sampler2d`, `Sampler3d`, `SamplerCube`).
    Sampler(SamplerId),
    /// A scene node to trace into (a program's `Object`).
    Object(NodeId),
}

impl std::fmt::Debug for VarValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            VarValue::Data { layout, words, .. } => write!(f, "{}{words:?}", layout.rust),
            VarValue::Buffer(b) => write!(f, "{b:?}"),
            VarValue::Sampler(s) => write!(f, "{s:?}"),
            VarValue::Object(n) => write!(f, "{n:?}"),
        }
    }
}

impl VarValue {
    /// How the value's type is spelled in messages (a buffer's and a
    /// sampler's as the scene's records say: element type, shape).
    pub fn type_name(&self, buffers: &dyn Fn(BufferId) -> String, samplers: &dyn Fn(SamplerId) -> String) -> String {
        match self {
            VarValue::Data { layout, .. } => layout.rust.to_string(),
            VarValue::Buffer(b) => buffers(*b),
            VarValue::Sampler(s) => samplers(*s),
            VarValue::Object(_) => "Object".into(),
        }
    }
}

/// Values that can be assigned to variables.
pub trait IntoVariable {
    /// The value as a variable holds it.
    fn into_variable(self) -> VarValue;
}

impl<T: RtData + Send + Sync> IntoVariable for T {
    fn into_variable(self) -> VarValue {
        let mut words = vec![0u32; T::LAYOUT.words as usize];
        self.write_words(&mut words);
        VarValue::Data { layout: T::LAYOUT, words, value: Arc::new(self) }
    }
}

impl IntoVariable for BufferId {
    fn into_variable(self) -> VarValue {
        VarValue::Buffer(self)
    }
}

impl IntoVariable for SamplerId {
    fn into_variable(self) -> VarValue {
        VarValue::Sampler(self)
    }
}

impl IntoVariable for NodeId {
    fn into_variable(self) -> VarValue {
        VarValue::Object(self)
    }
}

/// The variables set on one scope.
#[derive(Clone, Debug, Default)]
pub struct VarScope {
    vars: BTreeMap<String, VarValue>,
}

impl VarScope {
    /// Sets `name`, replacing any value it had.
    pub fn set(&mut self, name: &str, value: VarValue) {
        self.vars.insert(name.to_string(), value);
    }

    /// The value of `name`, if set here.
    pub fn get(&self, name: &str) -> Option<&VarValue> {
        self.vars.get(name)
    }

    /// Unsets `name`, returning the value it had.
    pub fn remove(&mut self, name: &str) -> Option<VarValue> {
        self.vars.remove(name)
    }

    /// The names set here, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.vars.keys().map(String::as_str)
    }
}
