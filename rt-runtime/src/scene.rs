//! The scene graph: geometry, materials, geometry instances and the nodes
//! above them, as in OptiX. Handles are small copyable ids into the
//! context's tables.

use crate::accel::Acceleration;
use crate::vars::VarScope;
use glam::{Mat4, Vec2, Vec3};

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

impl NodeId {
    /// The handle programs receive for this node.
    pub fn object(self) -> rt_std::Object {
        rt_std::Object::new(self.0)
    }
}

/// A triangle mesh in object space.
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    pub positions: Vec<Vec3>,
    /// Three vertex indices per triangle.
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex normals, for shading normals.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates.
    pub texcoords: Option<Vec<Vec2>>,
    /// Per-triangle material index (into the instance's materials); 0 when
    /// absent.
    pub material_indices: Option<Vec<u32>>,
}

impl TriangleMesh {
    /// The vertices of triangle `t`.
    #[inline]
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        self.indices[t].map(|i| self.positions[i as usize])
    }

    /// Checks indices and values; the message names the first problem.
    pub fn validate(&self) -> Result<(), String> {
        if self.indices.is_empty() {
            return Err("the mesh has no triangles".into());
        }
        check_positions(&self.positions)?;
        let n = self.positions.len() as u32;
        for (t, tri) in self.indices.iter().enumerate() {
            if let Some(bad) = tri.iter().find(|&&i| i >= n) {
                return Err(format!("triangle {t} uses vertex {bad}, but there are {n} vertices"));
            }
        }
        for (what, len) in
            [("normals", self.normals.as_ref().map(Vec::len)), ("texcoords", self.texcoords.as_ref().map(Vec::len))]
        {
            if let Some(len) = len
                && len != self.positions.len()
            {
                return Err(format!("{len} {what} for {n} vertices"));
            }
        }
        if let Some(m) = &self.material_indices
            && m.len() != self.indices.len()
        {
            return Err(format!("{} material indices for {} triangles", m.len(), self.indices.len()));
        }
        Ok(())
    }
}

/// Vertex positions must be finite.
pub(crate) fn check_positions(positions: &[Vec3]) -> Result<(), String> {
    match positions.iter().position(|p| !p.is_finite()) {
        Some(i) => Err(format!("vertex {i} has a non-finite position {:?}", positions[i])),
        None => Ok(()),
    }
}

/// What a geometry is made of.
#[derive(Clone, Debug)]
pub enum GeometryKind {
    /// Built-in triangles: the runtime intersects them (watertight) and fills
    /// the hit programs' attributes by field name: `geometric_normal`,
    /// `shading_normal` (Vec3, object space), `texcoord`, `barycentrics`
    /// (Vec2).
    Triangles(TriangleMesh),
    /// Custom primitives: an intersection and a bounding-box program.
    Custom { primitive_count: u32, intersection: crate::ProgramId, bounding_box: crate::ProgramId },
}

pub(crate) struct GeometryRec {
    pub kind: GeometryKind,
    pub vars: VarScope,
}

pub(crate) struct MaterialRec {
    pub closest_hit: Vec<Option<crate::ProgramId>>,
    pub any_hit: Vec<Option<crate::ProgramId>>,
    pub vars: VarScope,
}

pub(crate) struct GeometryInstanceRec {
    pub geometry: GeometryId,
    pub materials: Vec<MaterialId>,
    pub vars: VarScope,
}

pub(crate) enum NodeKind {
    GeometryGroup { children: Vec<GeometryInstanceId>, accel: Acceleration },
    Group { children: Vec<NodeId>, accel: Acceleration },
    Transform { matrix: Mat4, inverse: Mat4, child: NodeId },
    Selector { visit: crate::ProgramId, children: Vec<NodeId> },
}

pub(crate) struct NodeRec {
    pub kind: NodeKind,
    /// Rays whose mask shares no bit with this are not traced into it.
    pub visibility_mask: u8,
    pub vars: VarScope,
}
