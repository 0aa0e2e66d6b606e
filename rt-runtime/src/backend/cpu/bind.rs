//! Every program use of a launch resolved ([`link_all`]: variables by
//! scope, per instance, material and ray type) and bound to its program's
//! parameter types ([`Linked::bind`]), once per launch; attribute types
//! resolved with them.

use super::super::Settings;
use crate::accel::cache::NodeAccel;
use crate::buffer::SamplerShape;
use crate::error::{LinkError, Result};
use crate::link::{self, Call, Record};
use crate::scene::{GeometryKind, NodeId, NodeKind, Scene, TriangleMesh};
use crate::vertex_motion::VertexMotion;
use glam::UVec2;
use rt_std::cpu::{BoundVariables, Transforms};
use rt_std::program::{AttributesFromWords, ProgramDescriptor, TypeLayout};
use std::any::{Any, TypeId};
use std::sync::Arc;

/// Closest hit and any hit of one (instance, material, ray type).
pub(crate) type HitPrograms<P> = (Option<P>, Option<P>);

/// Every program use of a launch, resolved: `P` is [`Call`] (variables
/// owned) after linking, [`Program`] (variables bound) while running.
pub(crate) struct Linked<'a, P> {
    pub(crate) scene: &'a Scene,
    pub(crate) settings: &'a Settings,
    pub(crate) accels: &'a [Option<NodeAccel>],
    pub(crate) ray_generation: P,
    pub(crate) exception: Option<P>,
    /// Per ray type; `None` where the ray type has no miss program (a miss
    /// then does nothing, as in OptiX).
    pub(crate) miss: Vec<Option<P>>,
    /// `[instance][material slot][ray type]` → (closest hit, any hit).
    pub(crate) hits: Vec<Vec<Vec<HitPrograms<P>>>>,
    /// `[instance][ray type]`: whether some material of the instance has an
    /// any-hit program for the ray type (if not, triangle hits commit
    /// without building attributes).
    pub(crate) any_hit: Vec<Vec<bool>>,
    /// The triangles of each instance (None: custom geometry).
    pub(crate) meshes: Vec<Option<&'a TriangleMesh>>,
    /// The vertex motion of each instance's triangles (None: fixed
    /// vertices, or custom geometry).
    pub(crate) vertex_motion: Vec<Option<&'a VertexMotion>>,
    /// Intersection program per instance (custom geometry only).
    pub(crate) intersection: Vec<Option<P>>,
    /// Visit program per node (selectors only).
    pub(crate) visit: Vec<Option<P>>,
    /// Per program, a linked callable's use, for its `#[var]` variables
    /// (callables without variables: `None`).
    pub(crate) callables: Vec<Option<P>>,
    /// Per node, where its children's instances start, counted from its
    /// own first (groups and selectors; see [`link::instances`]).
    pub(crate) instance_offsets: Vec<Vec<u32>>,
    /// The launch's size as programs see it: width and height (of a 3D
    /// launch's slice), and depth (1 but for 3D launches, whose grid
    /// indices run over the slices' rows in turn).
    pub(crate) launch_dim: UVec2,
    /// The handles bindless ids read through, by buffer index.
    pub(crate) bindless: Arc<[BindlessHandles]>,
    /// The samplers bindless sampler ids read (a `Sampler2d`, `Sampler3d`
    /// or `SamplerCube` by shape), by sampler index.
    pub(crate) samplers: Arc<[Box<dyn Any + Send + Sync>]>,
    /// The launch's depth (see `launch_dim`).
    pub(crate) launch_depth: u32,
    /// Per node, a transform node's own matrices (without motion), where
    /// a program's context can borrow them: a ray under one transform
    /// copies no matrices.
    pub(crate) transforms: Arc<[Option<Transforms>]>,
}

/// One buffer's handles for bindless ids (`rt_std::BindlessBuffer<T>`):
/// a one-dimensional `Buffer<T>` over its elements, and an `RwBuffer<T>`
/// when programs may write it.
pub(crate) struct BindlessHandles {
    pub(crate) read: Box<dyn Any + Send + Sync>,
    pub(crate) write: Option<Box<dyn Any + Send + Sync>>,
}

impl BindlessHandles {
    /// The handles of every buffer of `scene`.
    fn of(scene: &Scene) -> Arc<[BindlessHandles]> {
        scene
            .buffers
            .iter()
            .map(|b| {
                let size = [b.len(), 1, 1];
                BindlessHandles {
                    read: b.storage.handle(1, false, size),
                    write: b.ty.writable_by_programs().then(|| b.storage.handle(1, true, size)),
                }
            })
            .collect()
    }
}

/// The handle of every sampler of `scene` for bindless sampler ids
/// (`rt_std::BindlessSampler<S>`), of the sampler type its shape reads as.
fn sampler_handles(scene: &Scene) -> Arc<[Box<dyn Any + Send + Sync>]> {
    scene
        .samplers
        .iter()
        .map(|s| -> Box<dyn Any + Send + Sync> {
            match s.shape {
                SamplerShape::Flat => Box::new(s.handle()),
                SamplerShape::Volume(_) => Box::new(s.handle_3d()),
                SamplerShape::Cube => Box::new(s.handle_cube()),
            }
        })
        .collect()
}

/// What each geometry instance's hits run: per material and ray type, its
/// closest-hit and any-hit uses; per ray type, whether any material has an
/// any-hit program; its mesh, vertex motion or intersection program.
struct InstanceUses<'a> {
    hits: Vec<Vec<Vec<HitPrograms<Call>>>>,
    any_hit: Vec<Vec<bool>>,
    meshes: Vec<Option<&'a TriangleMesh>>,
    vertex_motion: Vec<Option<&'a VertexMotion>>,
    intersection: Vec<Option<Call>>,
}

/// Resolves every geometry instance's program uses (see [`InstanceUses`]).
fn instance_uses(scene: &Scene) -> Result<InstanceUses<'_>> {
    let mut hits = Vec::with_capacity(scene.instances.len());
    let mut any_hit = Vec::with_capacity(scene.instances.len());
    let mut meshes = Vec::with_capacity(scene.instances.len());
    let mut vertex_motion = Vec::with_capacity(scene.instances.len());
    let mut intersection = Vec::with_capacity(scene.instances.len());
    for (i, gi) in scene.instances.iter().enumerate() {
        let instance = Some(crate::handles::GeometryInstanceId(i as u32));
        let mut per_material = Vec::new();
        let mut with_any_hit = vec![false; scene.ray_type_count() as usize];
        for m in &gi.materials {
            let mat = &scene.materials[m.index() as usize];
            let record = Record { instance, material: Some(*m), ..Record::default() };
            let mut per_ray = Vec::new();
            for (r, (ch, ah)) in mat.closest_hit.iter().zip(&mat.any_hit).enumerate() {
                if let Some(flag) = with_any_hit.get_mut(r) {
                    *flag |= ah.is_some();
                }
                per_ray.push((
                    ch.map(|p| link::resolve(scene, p, record)).transpose()?,
                    ah.map(|p| link::resolve(scene, p, record)).transpose()?,
                ));
            }
            per_material.push(per_ray);
        }
        hits.push(per_material);
        any_hit.push(with_any_hit);
        let geometry = &scene.geometries[gi.geometry.index() as usize];
        vertex_motion.push(geometry.vertex_motion.as_deref());
        match &geometry.kind {
            GeometryKind::Custom { intersection: p, .. } => {
                meshes.push(None);
                intersection.push(Some(link::resolve(
                    scene,
                    *p,
                    Record { instance, geometry: Some(gi.geometry), ..Record::default() },
                )?));
            }
            GeometryKind::Triangles(mesh) => {
                meshes.push(Some(mesh));
                intersection.push(None);
            }
        }
    }
    Ok(InstanceUses { hits, any_hit, meshes, vertex_motion, intersection })
}

pub(crate) fn link_all<'a>(
    scene: &'a Scene,
    settings: &'a Settings,
    accels: &'a [Option<NodeAccel>],
    entry: u32,
    (dim, depth): (UVec2, u32),
) -> Result<Linked<'a, Call>> {
    let count = scene.entry_points.len() as u32;
    let ep = scene.entry_points.get(entry as usize).ok_or(LinkError::NoSuchEntryPoint { entry, count })?;
    let rg = ep.ray_generation.ok_or(LinkError::NoRayGeneration { entry })?;
    link::check_types(scene)?;
    let ray_generation = link::resolve(scene, rg, Record::default())?;
    let exception = ep.exception.map(|p| link::resolve(scene, p, Record::default())).transpose()?;
    let miss = scene
        .miss
        .iter()
        .map(|m| m.map(|p| link::resolve(scene, p, Record::default())).transpose())
        .collect::<Result<Vec<_>>>()?;
    let InstanceUses { hits, any_hit, meshes, vertex_motion, intersection } = instance_uses(scene)?;
    let visit = scene
        .nodes
        .iter()
        .enumerate()
        .map(|(n, rec)| match rec.kind {
            NodeKind::Selector { visit, .. } => {
                link::resolve(scene, visit, Record { node: Some(NodeId(n as u32)), ..Record::default() }).map(Some)
            }
            _ => Ok(None),
        })
        .collect::<Result<Vec<_>>>()?;
    // The callables these programs may call, refused in a cycle as the wgpu
    // kernel refuses them (a direct call would recurse, maybe forever).
    let callers = std::iter::once(&ray_generation)
        .chain(&exception)
        .chain(miss.iter().flatten())
        .chain(hits.iter().flatten().flatten().flat_map(|(ch, ah)| ch.iter().chain(ah)))
        .chain(intersection.iter().flatten())
        .chain(visit.iter().flatten())
        .map(|c| c.desc);
    let (_, linked) = link::callables::linked(callers, &link::callables::scene_callables(scene))?;
    let mut callables: Vec<Option<Call>> = scene.programs.iter().map(|_| None).collect();
    for p in link::callables::with_variables(&linked) {
        callables[p.index() as usize] = Some(link::resolve(scene, p, Record::default())?);
    }
    let numbering = link::instances::Numbering::of(scene)?;
    let instance_offsets = scene
        .nodes
        .iter()
        .map(|rec| match &rec.kind {
            NodeKind::Group { children, .. } | NodeKind::Selector { children, .. } => numbering.offsets(children),
            _ => Vec::new(),
        })
        .collect();
    Ok(Linked {
        scene,
        settings,
        accels,
        ray_generation,
        exception,
        miss,
        hits,
        any_hit,
        meshes,
        vertex_motion,
        intersection,
        visit,
        callables,
        instance_offsets,
        launch_dim: dim,
        bindless: BindlessHandles::of(scene),
        samplers: sampler_handles(scene),
        launch_depth: depth,
        transforms: scene
            .nodes
            .iter()
            .map(|n| match &n.kind {
                NodeKind::Transform { matrix, inverse, motion: None, .. } => {
                    Some(Transforms { object_to_world: *matrix, world_to_object: *inverse })
                }
                _ => None,
            })
            .collect(),
    })
}

impl<'a> Linked<'a, Call> {
    /// The same uses with their variables bound to their programs, for the
    /// run.
    pub(crate) fn bind(&self) -> Result<Linked<'_, Program<'_>>> {
        fn opt(c: &Option<Call>) -> Result<Option<Program<'_>>> {
            c.as_ref().map(Program::bind).transpose()
        }
        Ok(Linked {
            scene: self.scene,
            settings: self.settings,
            accels: self.accels,
            ray_generation: Program::bind(&self.ray_generation)?,
            exception: opt(&self.exception)?,
            miss: self.miss.iter().map(opt).collect::<Result<_>>()?,
            hits: self
                .hits
                .iter()
                .map(|m| m.iter().map(|r| r.iter().map(|(ch, ah)| Ok((opt(ch)?, opt(ah)?))).collect()).collect())
                .collect::<Result<_>>()?,
            any_hit: self.any_hit.clone(),
            meshes: self.meshes.clone(),
            vertex_motion: self.vertex_motion.clone(),
            intersection: self.intersection.iter().map(opt).collect::<Result<_>>()?,
            visit: self.visit.iter().map(opt).collect::<Result<_>>()?,
            callables: self.callables.iter().map(opt).collect::<Result<_>>()?,
            instance_offsets: self.instance_offsets.clone(),
            launch_dim: self.launch_dim,
            bindless: self.bindless.clone(),
            samplers: self.samplers.clone(),
            launch_depth: self.launch_depth,
            transforms: self.transforms.clone(),
        })
    }
}

/// A program use ready to call: its variables bound to its parameter types
/// (checked once here, read per call without a check), and its attribute
/// type.
pub(crate) struct Program<'a> {
    pub(crate) desc: &'static ProgramDescriptor,
    pub(crate) call: &'a Call,
    pub(crate) vars: BoundVariables<'a>,
    pub(crate) attributes: Option<AttributeType>,
}

impl<'a> Program<'a> {
    pub(crate) fn bind(call: &'a Call) -> Result<Self> {
        let attributes = match (call.desc.attributes, call.desc.cpu_attributes) {
            (Some(layout), Some(make)) => Some(AttributeType::new(&layout, make)),
            _ => None,
        };
        let refs = link::var_refs(call);
        let vars = (call.desc.cpu_bind)(&refs[..call.vars.len()]).map_err(|e| link::bind_error(call, e))?;
        Ok(Program { desc: call.desc, call, vars, attributes })
    }
}

/// The attribute type a program takes, resolved once per launch: how to
/// make a value and how to recognise a reusable one.
pub(crate) struct AttributeType {
    pub(crate) id: TypeId,
    pub(crate) words: usize,
    pub(crate) make: AttributesFromWords,
}

/// Attribute structs up to this many words are zeroed on the stack.
pub(crate) const STACK_WORDS: usize = 64;

impl AttributeType {
    pub(crate) fn new(layout: &TypeLayout, make: AttributesFromWords) -> Self {
        let words = layout.words as usize;
        let id = Any::type_id(make(&vec![0; words]).as_any());
        AttributeType { id, words, make }
    }

    /// Runs `f` on zeroed heap words of this type.
    pub(crate) fn with_zero_words<R>(&self, f: impl FnOnce(&[u32]) -> R) -> R {
        // In a small buffer when that holds them (the usual attribute
        // struct: four stores rather than a `memset` call).
        let small = [0u32; 16];
        if self.words <= small.len() {
            f(&small[..self.words])
        } else if self.words <= STACK_WORDS {
            f(&[0u32; STACK_WORDS][..self.words])
        } else {
            f(&vec![0; self.words])
        }
    }
}
