//! Handles: small copyable ids into the scene's tables (programs,
//! geometries, materials, geometry instances, nodes, buffers, samplers).

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name(pub(crate) u32);
        impl $name {
            /// The index of this handle in its table.
            pub fn index(self) -> u32 {
                self.0
            }
        }
    };
}

handle!(
    /// A program created from a descriptor (a variable scope of its own).
    ProgramId
);
handle!(
    /// A geometry: triangles or custom primitives.
    GeometryId
);
handle!(
    /// A material: closest-hit and any-hit programs per ray type.
    MaterialId
);
handle!(
    /// A geometry with its materials.
    GeometryInstanceId
);
handle!(
    /// A node of the graph above geometry instances: geometry group, group,
    /// transform or selector. Programs trace against nodes (`Object`).
    NodeId
);
handle!(
    /// A buffer.
    BufferId
);
handle!(
    /// A texture sampler.
    SamplerId
);

/// Callable ids (`rt_std::Callable`) are program handles plus one, so that
/// zero is `Callable::NONE`, the id of no program.
impl ProgramId {
    /// The id programs call this program through.
    pub(crate) fn callable_id(self) -> u32 {
        self.0 + 1
    }

    /// The program callable id `id` names, if any (zero names none).
    pub(crate) fn from_callable_id(id: u32) -> Option<ProgramId> {
        id.checked_sub(1).map(ProgramId)
    }
}

/// Bindless buffer ids (`rt_std::BindlessBuffer`) are buffer handles plus
/// one, so that zero is `BindlessBuffer::NONE`, the id of no buffer.
impl BufferId {
    /// The id programs read this buffer through.
    pub(crate) fn bindless_id(self) -> u32 {
        self.0 + 1
    }

    /// The buffer bindless id `id` names, if any (zero names none).
    pub(crate) fn from_bindless_id(id: u32) -> Option<BufferId> {
        id.checked_sub(1).map(BufferId)
    }
}

/// Bindless sampler ids (`rt_std::BindlessSampler`) are sampler handles
/// plus one, so that zero is `BindlessSampler::NONE`, the id of no sampler.
impl SamplerId {
    /// The id programs sample this sampler through.
    pub(crate) fn bindless_id(self) -> u32 {
        self.0 + 1
    }

    /// The sampler bindless id `id` names, if any (zero names none).
    pub(crate) fn from_bindless_id(id: u32) -> Option<SamplerId> {
        id.checked_sub(1).map(SamplerId)
    }
}

impl NodeId {
    /// The handle programs receive for this node.
    pub fn object(self) -> rt_std::Object {
        rt_std::Object::new(self.0)
    }
}
