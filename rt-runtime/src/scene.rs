//! The scene graph: programs, geometry, materials, geometry instances and
//! the nodes above them, as in OptiX, with buffers, samplers, variables and
//! entry points: everything a launch runs over (`Scene`). Handles
//! (`crate::handles`) are small copyable ids into its tables. The context
//! owns one and edits it; backends read it.

use crate::buffer::{BufferRec, SamplerRec};
use crate::error::{Result, SceneError};
use crate::motion::MotionTransform;
use crate::vars::VarScope;
use crate::vertex_motion::VertexMotion;
use glam::{Mat4, Vec2, Vec3};
use rt_std::program::ProgramDescriptor;

pub use crate::handles::{BufferId, GeometryId, GeometryInstanceId, MaterialId, NodeId, ProgramId, SamplerId};

/// A triangle mesh in object space.
#[derive(Clone, Debug, Default)]
pub struct TriangleMesh {
    /// Vertex positions.
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
    Custom {
        /// How many primitives (the programs' `prim` runs from 0 to this).
        primitive_count: u32,
        /// The program that intersects a ray with one primitive.
        intersection: ProgramId,
        /// The program that bounds one primitive.
        bounding_box: ProgramId,
    },
}

pub(crate) struct GeometryRec {
    pub kind: GeometryKind,
    pub vars: VarScope,
    /// A triangle mesh's vertex motion keys (its positions are the first
    /// key's).
    pub vertex_motion: Option<Box<VertexMotion>>,
}

pub(crate) struct MaterialRec {
    pub closest_hit: Vec<Option<ProgramId>>,
    pub any_hit: Vec<Option<ProgramId>>,
    pub vars: VarScope,
}

pub(crate) struct GeometryInstanceRec {
    pub geometry: GeometryId,
    pub materials: Vec<MaterialId>,
    pub vars: VarScope,
    /// What `instance_id()` returns on its hits (`INSTANCE_ID_NONE`: none
    /// set; see [`crate::link::instances`]).
    pub instance_id: u32,
}

pub(crate) enum NodeKind {
    GeometryGroup {
        children: Vec<GeometryInstanceId>,
        accel: Acceleration,
    },
    Group {
        children: Vec<NodeId>,
        accel: Acceleration,
    },
    /// `matrix` and `inverse` are the static transform's; a motion
    /// transform has `motion` (and its first key as `matrix`).
    Transform {
        matrix: Mat4,
        inverse: Mat4,
        child: NodeId,
        motion: Option<Box<MotionTransform>>,
    },
    Selector {
        visit: ProgramId,
        children: Vec<NodeId>,
    },
}

pub(crate) struct NodeRec {
    pub kind: NodeKind,
    /// Rays whose mask shares no bit with this are not traced into it.
    pub visibility_mask: u8,
    pub vars: VarScope,
    /// The instance id of the geometry below (transforms only;
    /// `INSTANCE_ID_NONE`: none set).
    pub instance_id: u32,
}

pub(crate) struct ProgramRec {
    pub desc: &'static ProgramDescriptor,
    pub vars: VarScope,
}

#[derive(Clone, Copy, Default)]
pub(crate) struct EntryPoint {
    pub ray_generation: Option<ProgramId>,
    pub exception: Option<ProgramId>,
}

/// Where a variable is set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// The context: every program's outermost scope.
    Context,
    /// A program: the innermost scope of its own variables.
    Program(ProgramId),
    /// A geometry (read by its intersection and bounding-box programs).
    Geometry(GeometryId),
    /// A geometry instance (read by hit, intersection and bounding-box
    /// programs).
    GeometryInstance(GeometryInstanceId),
    /// A material (read by its hit programs).
    Material(MaterialId),
    /// A node (read by a selector's visit program).
    Node(NodeId),
}

impl From<ProgramId> for Scope {
    fn from(p: ProgramId) -> Scope {
        Scope::Program(p)
    }
}
impl From<GeometryId> for Scope {
    fn from(g: GeometryId) -> Scope {
        Scope::Geometry(g)
    }
}
impl From<GeometryInstanceId> for Scope {
    fn from(g: GeometryInstanceId) -> Scope {
        Scope::GeometryInstance(g)
    }
}
impl From<MaterialId> for Scope {
    fn from(m: MaterialId) -> Scope {
        Scope::Material(m)
    }
}
impl From<NodeId> for Scope {
    fn from(n: NodeId) -> Scope {
        Scope::Node(n)
    }
}

/// Everything a launch runs over: the tables the handles index, the
/// context's variables, entry points and miss programs, and the versions
/// that tell a backend what changed since its last launch.
pub(crate) struct Scene {
    pub programs: Vec<ProgramRec>,
    pub geometries: Vec<GeometryRec>,
    pub materials: Vec<MaterialRec>,
    pub instances: Vec<GeometryInstanceRec>,
    pub nodes: Vec<NodeRec>,
    pub buffers: Vec<BufferRec>,
    pub samplers: Vec<SamplerRec>,
    pub vars: VarScope,
    pub entry_points: Vec<EntryPoint>,
    pub miss: Vec<Option<ProgramId>>,
    /// Bumped by every change but variable values and buffer contents: a
    /// wgpu launch re-encodes the scene only when it moved (with the
    /// acceleration structures' builds and refits).
    pub structure_version: u64,
    /// Bumped by every change to geometries, geometry instances and
    /// geometry groups: the part of the scene a wgpu launch keeps on the
    /// device while other things change.
    pub geometry_version: u64,
}

impl Default for Scene {
    /// One entry point and one ray type, nothing else.
    fn default() -> Self {
        Scene {
            programs: Vec::new(),
            geometries: Vec::new(),
            materials: Vec::new(),
            instances: Vec::new(),
            nodes: Vec::new(),
            buffers: Vec::new(),
            samplers: Vec::new(),
            vars: VarScope::default(),
            entry_points: vec![EntryPoint::default()],
            miss: vec![None],
            structure_version: 0,
            geometry_version: 0,
        }
    }
}

impl Scene {
    pub fn program(&self, p: ProgramId) -> Result<&ProgramRec> {
        self.programs.get(p.0 as usize).ok_or_else(|| SceneError::InvalidHandle(format!("{p:?}")).into())
    }

    pub fn ray_type_count(&self) -> u32 {
        self.miss.len() as u32
    }

    /// No any-hit and no intersection program in use: every primitive is a
    /// triangle that does not move with the ray's time and every candidate
    /// commits, so the wgpu kernel searches instances with its lean loop
    /// over CWBVHs (whose triangle slots hold fixed vertices). (Any-hit programs sit in
    /// materials' slots, intersection programs come with custom geometry:
    /// none among the instances', none in the kernel.)
    pub fn searches_triangles_only(&self) -> bool {
        self.instances.iter().all(|gi| {
            let g = &self.geometries[gi.geometry.index() as usize];
            matches!(g.kind, GeometryKind::Triangles(_))
                && g.vertex_motion.is_none()
                && gi.materials.iter().all(|m| self.materials[m.index() as usize].any_hit.iter().all(Option::is_none))
        })
    }

    /// The variables set on `scope`.
    pub fn scope(&self, scope: Scope) -> Result<&VarScope> {
        let missing = || SceneError::InvalidHandle(format!("{scope:?}"));
        Ok(match scope {
            Scope::Context => &self.vars,
            Scope::Program(p) => &self.programs.get(p.0 as usize).ok_or_else(missing)?.vars,
            Scope::Geometry(g) => &self.geometries.get(g.0 as usize).ok_or_else(missing)?.vars,
            Scope::GeometryInstance(g) => &self.instances.get(g.0 as usize).ok_or_else(missing)?.vars,
            Scope::Material(m) => &self.materials.get(m.0 as usize).ok_or_else(missing)?.vars,
            Scope::Node(n) => &self.nodes.get(n.0 as usize).ok_or_else(missing)?.vars,
        })
    }

    pub fn scope_mut(&mut self, scope: Scope) -> Result<&mut VarScope> {
        let missing = || SceneError::InvalidHandle(format!("{scope:?}"));
        Ok(match scope {
            Scope::Context => &mut self.vars,
            Scope::Program(p) => &mut self.programs.get_mut(p.0 as usize).ok_or_else(missing)?.vars,
            Scope::Geometry(g) => &mut self.geometries.get_mut(g.0 as usize).ok_or_else(missing)?.vars,
            Scope::GeometryInstance(g) => &mut self.instances.get_mut(g.0 as usize).ok_or_else(missing)?.vars,
            Scope::Material(m) => &mut self.materials.get_mut(m.0 as usize).ok_or_else(missing)?.vars,
            Scope::Node(n) => &mut self.nodes.get_mut(n.0 as usize).ok_or_else(missing)?.vars,
        })
    }
}

/// The nodes reachable from `roots`, children before parents; a cycle is an
/// error.
pub(crate) fn nodes_post_order(scene: &Scene) -> Result<Vec<NodeId>> {
    let mut state = vec![0u8; scene.nodes.len()];
    let mut order = Vec::new();
    fn visit(scene: &Scene, n: usize, state: &mut [u8], order: &mut Vec<NodeId>) -> Result<()> {
        match state[n] {
            1 => return Err(SceneError::GraphCycle { node: n as u32 }.into()),
            2 => return Ok(()),
            _ => {}
        }
        state[n] = 1;
        let children: Vec<NodeId> = match &scene.nodes[n].kind {
            NodeKind::Group { children, .. } | NodeKind::Selector { children, .. } => children.clone(),
            NodeKind::Transform { child, .. } => vec![*child],
            NodeKind::GeometryGroup { .. } => Vec::new(),
        };
        for c in children {
            visit(scene, c.index() as usize, state, order)?;
        }
        state[n] = 2;
        order.push(NodeId(n as u32));
        Ok(())
    }
    for n in 0..scene.nodes.len() {
        visit(scene, n, &mut state, &mut order)?;
    }
    Ok(order)
}

/// An acceleration builder, by OptiX's names (how each maps onto obvhs:
/// [`crate::accel`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Builder {
    /// BVH2, obvhs' medium-quality build: the general-purpose default.
    Bvh,
    /// BVH2 with spatial splits: highest quality; triangles only.
    Sbvh,
    /// BVH2, obvhs' fast build: lower quality.
    MedianBvh,
    /// BVH2, obvhs' fastest build.
    Lbvh,
    /// OptiX's kd-tree, which obvhs does not build: asking for it is an
    /// error.
    TriangleKdTree,
    /// One leaf holding every primitive: a linear scan.
    NoAccel,
}

impl Builder {
    /// OptiX's name for the builder (`"Bvh"`, `"Sbvh"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Builder::Bvh => "Bvh",
            Builder::Sbvh => "Sbvh",
            Builder::MedianBvh => "MedianBvh",
            Builder::Lbvh => "Lbvh",
            Builder::TriangleKdTree => "TriangleKdTree",
            Builder::NoAccel => "NoAccel",
        }
    }

    /// Parses OptiX's builder names.
    pub fn from_name(name: &str) -> Option<Builder> {
        [Builder::Bvh, Builder::Sbvh, Builder::MedianBvh, Builder::Lbvh, Builder::TriangleKdTree, Builder::NoAccel]
            .into_iter()
            .find(|b| b.name() == name)
    }
}

/// An acceleration structure attached to a geometry group or group.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Acceleration {
    /// How the structure is built.
    pub builder: Builder,
}

impl Acceleration {
    /// A structure built by `builder`.
    pub fn new(builder: Builder) -> Self {
        Acceleration { builder }
    }
}

impl Default for Acceleration {
    fn default() -> Self {
        Acceleration::new(Builder::Bvh)
    }
}
