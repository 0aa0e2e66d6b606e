//! Handles to the scene graph: [`Object`] and the transforms
//! ([`TransformKind`]) of the instance being intersected or shaded.

/// A node of the scene graph that rays can be traced against (a group,
/// geometry group, transform or selector), as a variable gives it to a
/// program. It is a plain id: the runtime resolves it when
/// [`rt_trace`](crate::rt_trace) is called.
#[doc(alias = "rtObject")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Object {
    /// The node's id in the runtime's scene graph.
    pub id: u32,
}

impl Object {
    /// The handle of node `id`.
    ///
    /// Program kinds: all.
    pub const fn new(id: u32) -> Object {
        Object { id }
    }
}

/// Which way a transform intrinsic
/// ([`rt_transform_point`](crate::rt_transform_point) and its siblings)
/// maps: between the current geometry instance's object space and world
/// space. The prelude imports the variants, so programs write
/// `rt_transform_normal(ObjectToWorld, n)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TransformKind {
    /// From object space to world space.
    #[doc(alias = "RT_OBJECT_TO_WORLD")]
    ObjectToWorld,
    /// From world space to object space.
    #[doc(alias = "RT_WORLD_TO_OBJECT")]
    WorldToObject,
}
