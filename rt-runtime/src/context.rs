//! The context: programs, the scene graph, variables, buffers and launches.

use crate::accel::Acceleration;
use crate::accel::cache::AccelCache;
use crate::backend::tiles::{LaunchControl, LaunchProgress, Pace, Tile, TileBudget};
use crate::backend::wgpu::{Gpu, WgpuBackend};
use crate::backend::{self, Backend, LaunchBackend, LaunchReport, Pacing, Settings};
use crate::buffer::{BufferRec, BufferType, SamplerRec, SamplerShape, Typed};
use crate::error::{Result, RtError};
use crate::motion::{MotionKeys, MotionTransform};
use crate::scene::*;
use crate::usage::UsageReport;
use crate::vars::{IntoVariable, VarScope};
use crate::vertex_motion::VertexMotion;
use std::any::Any;

pub use crate::scene::Scope;
use glam::{Mat4, Vec4};
use rt_std::program::{ProgramDescriptor, ProgramKind};
use rt_std::{FilterMode, IndexMode, MipFilter, RtData, SamplerModes, WrapMode};

mod device_buffers;
pub use device_buffers::{DeviceBuffer, WgpuDevice};

/// A ray-tracing context: the root of everything, as in OptiX.
///
/// It holds the scene it edits ([`Scene`]), the launch settings, the
/// acceleration structures built for the scene, and the backend launches
/// run on, behind [`LaunchBackend`]. A backend it ran on before (or opened
/// ahead, [`Context::open_wgpu`]) is kept, with its device and its
/// statistics, for when the context switches back.
///
/// A context is `Send` and `Sync`: it may move to another thread, and
/// `&Context` (reading buffers, statistics) may be shared; launches and
/// edits take `&mut`. Contexts on several threads run at once, each CPU
/// launch on rayon's shared pool, and wgpu contexts with a device each or
/// sharing one ([`Context::use_wgpu_device`] with clones of one device and
/// queue): `tests/tests/concurrency.rs` checks that they render what a
/// serial run does.
pub struct Context {
    pub(crate) scene: Scene,
    pub(crate) settings: Settings,
    pub(crate) accels: AccelCache,
    backend: Box<dyn LaunchBackend>,
    parked: Vec<Box<dyn LaunchBackend>>,
    /// How long an index of each entry point took, for sizing tiles.
    pace: Pace,
    /// Called after every launch ([`Context::set_usage_report`]).
    usage_report: Option<UsageCallback>,
}

/// A kind of exception whose checks [`Context::set_exception_enabled`]
/// turns on or off (OptiX 6's `RT_EXCEPTION_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExceptionKind {
    /// `rt_trace` at the maximum trace depth (`EXCEPTION_TRACE_DEPTH_EXCEEDED`).
    TraceDepthExceeded,
    /// A buffer index out of bounds (`EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`).
    BufferIndexOutOfBounds,
    /// A NaN or infinite ray, or a payload its ray type's programs do not
    /// take (`EXCEPTION_INVALID_RAY`).
    InvalidRay,
    /// Integer overflow (CPU backend, with integer exceptions on).
    IntegerOverflow,
    /// Integer division by zero (CPU backend, with integer exceptions on).
    IntegerDivideByZero,
    /// A callable program called through an id that names none of its
    /// signature (OptiX `RT_EXCEPTION_PROGRAM_ID_INVALID`).
    ProgramIdInvalid,
    /// A buffer read or written through a bindless id that names no buffer
    /// of its element type (OptiX `RT_EXCEPTION_BUFFER_ID_INVALID`).
    BufferIdInvalid,
    /// A texture sampled through a bindless sampler id that names no
    /// sampler of its shape (OptiX `RT_EXCEPTION_TEXTURE_ID_INVALID`).
    TextureIdInvalid,
    /// `rt_throw`'s codes.
    User,
    /// Every kind.
    All,
}

impl ExceptionKind {
    fn bits(self) -> u32 {
        use rt_abi::constants::*;
        match self {
            ExceptionKind::TraceDepthExceeded => exception_kind_bit(EXCEPTION_TRACE_DEPTH_EXCEEDED),
            ExceptionKind::BufferIndexOutOfBounds => exception_kind_bit(EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS),
            ExceptionKind::InvalidRay => exception_kind_bit(EXCEPTION_INVALID_RAY),
            ExceptionKind::IntegerOverflow => exception_kind_bit(EXCEPTION_INTEGER_OVERFLOW),
            ExceptionKind::IntegerDivideByZero => exception_kind_bit(EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
            ExceptionKind::ProgramIdInvalid => exception_kind_bit(EXCEPTION_PROGRAM_ID_INVALID),
            ExceptionKind::BufferIdInvalid => exception_kind_bit(EXCEPTION_BUFFER_ID_INVALID),
            ExceptionKind::TextureIdInvalid => exception_kind_bit(EXCEPTION_TEXTURE_ID_INVALID),
            ExceptionKind::User => exception_kind_bit(EXCEPTION_USER),
            ExceptionKind::All => ALL_EXCEPTION_KINDS,
        }
    }
}

/// What [`Context::set_usage_report`] calls.
pub type UsageCallback = Box<dyn FnMut(&UsageReport) + Send + Sync>;

impl Default for Context {
    fn default() -> Self {
        Context::new()
    }
}

impl Context {
    /// An empty context with one entry point and one ray type, a maximum
    /// trace depth of 5, on the CPU backend.
    pub fn new() -> Self {
        Context {
            scene: Scene::default(),
            settings: Settings::default(),
            accels: Default::default(),
            backend: Backend::Cpu.create(),
            parked: Vec::new(),
            pace: Pace::default(),
            usage_report: None,
        }
    }

    /// The backend launches run on.
    pub fn backend(&self) -> Backend {
        self.backend.kind()
    }

    /// Chooses the backend launches run on.
    pub fn set_backend(&mut self, backend: Backend) {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.run_on(backend);
    }

    /// Makes `kind` the backend launches run on: the one kept from before,
    /// else a new one.
    fn run_on(&mut self, kind: Backend) {
        if self.backend.kind() == kind {
            return;
        }
        let next = match self.parked.iter().position(|b| b.kind() == kind) {
            Some(i) => self.parked.swap_remove(i),
            None => kind.create(),
        };
        let previous = std::mem::replace(&mut self.backend, next);
        self.parked.push(previous);
    }

    /// The active backend, then the parked ones.
    fn backends(&self) -> impl Iterator<Item = &dyn LaunchBackend> {
        std::iter::once(&*self.backend).chain(self.parked.iter().map(|b| &**b))
    }

    /// The wgpu backend, active or parked (a new one parked if there is
    /// none yet).
    fn wgpu_backend(&mut self) -> &mut WgpuBackend {
        if !self.backends().any(|b| b.kind() == Backend::Wgpu) {
            self.parked.push(Backend::Wgpu.create());
        }
        std::iter::once(&mut self.backend)
            .chain(self.parked.iter_mut())
            .find_map(|b| (&mut **b as &mut dyn Any).downcast_mut::<WgpuBackend>())
            .expect("added above")
    }

    /// Runs launches on a wgpu device the application already has.
    pub fn use_wgpu_device(&mut self, device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo) {
        let _ = self.settle_device_buffers(None);
        self.wgpu_backend().use_device(Gpu::from_device(device, queue, info));
        self.run_on(Backend::Wgpu);
    }

    /// Opens the wgpu device now (launches do it on first use), returning the
    /// adapter's description.
    pub fn open_wgpu(&mut self) -> Result<String> {
        self.wgpu_backend().open()
    }

    /// How many full acceleration builds and refits launches have done.
    pub fn acceleration_builds(&self) -> (u64, u64) {
        (self.accels.builds, self.accels.refits)
    }

    /// Testing recovery: the next wgpu launch destroys its device once its
    /// work is submitted, as a driver reset or a removed GPU would. That
    /// launch fails with [`RtError::DeviceLost`] and writes no outputs; the
    /// one after opens a new device.
    pub fn simulate_device_loss_in_next_launch(&mut self) {
        self.wgpu_backend().lose_device_in_next_launch();
    }

    /// How many wgpu launches encoded and uploaded the scene (tables, BVH
    /// nodes, triangles); the others found it on the device, unchanged
    /// since, and encoded only the variables and buffers.
    pub fn scene_encodes(&self) -> u64 {
        self.backends().map(|b| b.stats().scene_encodes).sum()
    }

    /// How many of those encodes also encoded the geometry (geometry groups'
    /// BVH nodes, primitive tables and triangles; meshes): the others kept
    /// it on the device and encoded only the rest (transforms, groups,
    /// programs, records) around it.
    pub fn geometry_encodes(&self) -> u64 {
        self.backends().map(|b| b.stats().geometry_encodes).sum()
    }

    /// How many wgpu pipelines (megakernel links) this context created.
    pub fn pipelines_created(&self) -> u64 {
        self.backends().map(|b| b.stats().pipelines_created).sum()
    }

    /// Bytes the last wgpu launch wrote to the device: the pages of the
    /// scene and of the heap (records, buffers, textures) that changed since
    /// the launch before, the log's counters and the launch uniform (0 before
    /// any wgpu launch).
    pub fn last_upload_bytes(&self) -> u64 {
        self.backends().map(|b| b.stats().last_upload_bytes).sum()
    }

    /// Bytes the last wgpu launch read back from its device: the output
    /// buffers (not the device-local ones, [`Context::set_buffer_device_local`]),
    /// the log's header and what it counted, and the timestamps.
    pub fn last_read_back_bytes(&self) -> u64 {
        self.backends().map(|b| b.stats().last_read_back_bytes).sum()
    }

    /// The megakernel WGSL of the last wgpu launch (`RT_DUMP_WGSL=1` also
    /// writes it to the temporary directory).
    pub fn linked_wgsl(&self) -> Option<&str> {
        self.backends().find_map(|b| b.stats().linked_wgsl)
    }

    /// How the wgpu backend walks the scene: [`Traversal::Auto`] (the
    /// default) takes hardware ray queries where a GPU has them and the
    /// scene allows (no selectors; masks along each path that one 8-bit
    /// mask says), else the compute traversal (also on software adapters
    /// such as lavapipe, whose ray queries are slower than it), and reads
    /// `RT_TRAVERSAL=compute|rayquery`; [`Traversal::RayQuery`] on an
    /// adapter without ray queries fails the launch with an error naming
    /// the adapter. The CPU backend ignores it.
    ///
    /// [`Traversal`]: crate::Traversal
    /// [`Traversal::Auto`]: crate::Traversal::Auto
    /// [`Traversal::RayQuery`]: crate::Traversal::RayQuery
    pub fn set_traversal(&mut self, traversal: crate::Traversal) {
        self.settings.traversal = traversal;
    }

    /// The traversal [`Context::set_traversal`] asked for.
    pub fn traversal_setting(&self) -> crate::Traversal {
        self.settings.traversal
    }

    /// The traversal the last wgpu launch used (`Compute` or `RayQuery`)
    /// and why; None before any wgpu launch.
    pub fn traversal(&self) -> Option<(crate::Traversal, &str)> {
        self.backends().find_map(|b| b.stats().traversal)
    }

    /// How many BLASes (one per kind of geometry in a geometry group) and
    /// TLASes (one per traced root) the ray-query traversal built: a moved
    /// transform rebuilds TLASes only, moved vertices the BLASes over them.
    pub fn ray_query_builds(&self) -> (u64, u64) {
        self.backends().fold((0, 0), |(b, t), s| (b + s.stats().blas_builds, t + s.stats().tlas_builds))
    }

    /// Per ray type, whether the last launch's ray-query traces of that type
    /// took the opaque path (the query forced opaque: no traced geometry
    /// has an any-hit program for the type, every material index is in
    /// range, so triangles commit without reaching the kernel); `None`
    /// unless the last launch used the ray-query traversal.
    pub fn ray_query_opaque_ray_types(&self) -> Option<Vec<bool>> {
        self.backends().find_map(|s| s.stats().opaque_ray_types.map(<[bool]>::to_vec))
    }

    pub fn set_entry_point_count(&mut self, n: u32) {
        self.scene.structure_version += 1;
        self.scene.entry_points.resize(n as usize, EntryPoint::default());
    }

    pub fn entry_point_count(&self) -> u32 {
        self.scene.entry_points.len() as u32
    }

    pub fn set_ray_type_count(&mut self, n: u32) {
        self.scene.structure_version += 1;
        self.scene.miss.resize(n as usize, None);
        for m in &mut self.scene.materials {
            m.closest_hit.resize(n as usize, None);
            m.any_hit.resize(n as usize, None);
        }
    }

    pub fn ray_type_count(&self) -> u32 {
        self.scene.ray_type_count()
    }

    /// Rays may nest this deep (primary rays are depth 1); a trace beyond it
    /// raises the trace-depth-exceeded exception instead.
    pub fn set_max_trace_depth(&mut self, depth: u32) {
        self.scene.structure_version += 1;
        self.settings.max_trace_depth = depth.max(1);
    }

    /// A debugging mode beyond OptiX, off by default: on the CPU backend,
    /// integer overflow (`+ - *`, negation, `abs`, shifts by 32 or more,
    /// `i32::MIN / -1`) raises [`EXCEPTION_INTEGER_OVERFLOW`](rt_std::EXCEPTION_INTEGER_OVERFLOW)
    /// and division or remainder by zero
    /// [`EXCEPTION_INTEGER_DIVIDE_BY_ZERO`](rt_std::EXCEPTION_INTEGER_DIVIDE_BY_ZERO),
    /// reported through the exception program and in the launch report's
    /// [`ExceptionRecord`](crate::ExceptionRecord) with the operator's file
    /// and line; the value is the wrapped one either way, and the program
    /// goes on. The wgpu backend computes the same values and raises
    /// nothing (off, both backends agree, as with Rust's release builds).
    pub fn set_integer_exceptions(&mut self, on: bool) {
        self.settings.integer_exceptions = on;
    }

    /// Turns the checks of exception kind `kind` on or off (all are on by
    /// default; OptiX 6's `rtContextSetExceptionEnabled`). A check that is
    /// off still guards its operation (a buffer index out of bounds still
    /// reads a default value and writes nothing; an invalid ray, or one past
    /// the trace depth, is still not traced: `tests/tests/exception_kinds.rs`
    /// asserts it on every backend) but raises nothing: the exception
    /// program does not run and the launch reports no record. The integer
    /// kinds also need [`Context::set_integer_exceptions`].
    #[doc(alias = "rtContextSetExceptionEnabled")]
    pub fn set_exception_enabled(&mut self, kind: ExceptionKind, on: bool) {
        let bits = kind.bits();
        if on {
            self.settings.exceptions |= bits;
        } else {
            self.settings.exceptions &= !bits;
        }
    }

    /// Whether every check of `kind` is on ([`Context::set_exception_enabled`]).
    pub fn exception_enabled(&self, kind: ExceptionKind) -> bool {
        self.settings.exceptions & kind.bits() == kind.bits()
    }

    /// Turns `rt_printf!` output on or off, and optionally limits it to one
    /// launch index (as OptiX's `rtContextSetPrintLaunchIndex`).
    pub fn set_print(&mut self, enabled: bool, launch_index: Option<glam::UVec2>) {
        self.settings.print_enabled = enabled;
        self.settings.print_launch_index = launch_index;
    }

    // ---- programs ----

    /// Creates a program from a descriptor (`my_program::PROGRAM`).
    pub fn create_program(&mut self, desc: &'static ProgramDescriptor) -> ProgramId {
        self.scene.structure_version += 1;
        self.scene.programs.push(ProgramRec { desc, vars: VarScope::default() });
        ProgramId(self.scene.programs.len() as u32 - 1)
    }

    /// The id programs call callable program `p` through, as a
    /// [`Callable<F>`](rt_std::Callable) of the signature `F` the program
    /// was declared with (`fn(Vec3, Vec3) -> Vec3`): set it as a variable,
    /// or store it in a buffer, payload or struct. Errors if `p` is not a
    /// callable program or its signature is not `F`, naming the program.
    #[doc(alias = "rtProgramGetId")]
    pub fn callable_id<F: 'static>(&self, p: ProgramId) -> Result<rt_std::Callable<F>> {
        let desc = self.scene.program(p)?.desc;
        let Some(callable) = desc.callable else {
            return Err(RtError::WrongProgramKind {
                program: desc.name,
                location: desc.location(),
                found: desc.kind,
                expected: ProgramKind::Callable,
                slot: "a callable id".into(),
            });
        };
        if !callable.cpu.is::<F>() {
            return Err(RtError::CallableSignature {
                program: desc.name,
                location: desc.location(),
                signature: callable.signature.rust,
                asked: short_type_name(std::any::type_name::<F>()),
            });
        }
        Ok(rt_std::Callable::from_id(p.callable_id()))
    }

    /// The bindless id of buffer `b` (OptiX `rtBufferGetId`): a
    /// [`BindlessBuffer<T>`](rt_std::BindlessBuffer) programs read the
    /// buffer through, set as a variable or stored in a buffer, payload or
    /// struct. Errors if the buffer's elements are not `T`, naming the
    /// buffer and both types. A two-dimensional buffer reads as its
    /// `width * height` elements, row by row.
    #[doc(alias = "rtBufferGetId")]
    pub fn buffer_id<T: RtData>(&self, b: BufferId) -> Result<rt_std::BindlessBuffer<T>> {
        self.check_bindless::<T>(b, false)?;
        Ok(rt_std::BindlessBuffer::from_id(b.bindless_id()))
    }

    /// The writable bindless id of buffer `b`, an
    /// [`RwBindlessBuffer<T>`](rt_std::RwBindlessBuffer): as
    /// [`buffer_id`](Self::buffer_id), and the buffer must be one programs
    /// may write (`Output` or `InputOutput`).
    #[doc(alias = "rtBufferGetId")]
    pub fn rw_buffer_id<T: RtData>(&self, b: BufferId) -> Result<rt_std::RwBindlessBuffer<T>> {
        self.check_bindless::<T>(b, true)?;
        Ok(rt_std::RwBindlessBuffer::from_id(b.bindless_id()))
    }

    /// The bindless id of sampler `s` (OptiX `rtTextureSamplerGetId`): a
    /// [`BindlessSampler<S>`](rt_std::BindlessSampler) programs sample
    /// through, set as a variable or stored in a buffer, payload or struct.
    /// `S` is the sampler's shape, [`Sampler2d`](rt_std::Sampler2d) for
    /// the 2D forms of `create_sampler*`, [`Sampler3d`](rt_std::Sampler3d)
    /// for `create_sampler_3d`, [`SamplerCube`](rt_std::SamplerCube) for
    /// `create_sampler_cube`; errors naming the sampler and both shapes if
    /// it is another. Ids are not bound to the adapter's sampled-texture
    /// slots (samplers live in the heap on every backend), so any number
    /// of samplers may have ids.
    #[doc(alias = "rtTextureSamplerGetId")]
    pub fn sampler_id<S: rt_std::bindless_sampler::SamplerShape>(
        &self,
        s: SamplerId,
    ) -> Result<rt_std::BindlessSampler<S>> {
        let rec =
            self.scene.samplers.get(s.index() as usize).ok_or_else(|| RtError::InvalidHandle(format!("{s:?}")))?;
        if rec.type_name() != S::NAME {
            return Err(RtError::BadSampler {
                sampler: s.index(),
                problem: format!(
                    "asked for a bindless id of a `{}`, but the sampler is a `{}` (ask for a `BindlessSampler<{}>`)",
                    S::NAME,
                    rec.type_name(),
                    rec.type_name()
                ),
            });
        }
        Ok(rt_std::BindlessSampler::from_id(s.bindless_id()))
    }

    fn check_bindless<T: RtData>(&self, b: BufferId, writable: bool) -> Result<()> {
        let rec = self.scene.buffers.get(b.index() as usize).ok_or_else(|| RtError::InvalidHandle(format!("{b:?}")))?;
        let held = rec.storage.layout().rust;
        if held != T::LAYOUT.rust {
            return Err(RtError::BadBuffer {
                buffer: b.index(),
                problem: format!(
                    "asked for a bindless id of `{}` elements, but the buffer holds `{held}` ({})",
                    T::LAYOUT.rust,
                    rec.type_name()
                ),
            });
        }
        if writable && !rec.ty.writable_by_programs() {
            return Err(RtError::BadBuffer {
                buffer: b.index(),
                problem: format!(
                    "asked for a writable bindless id, but programs may not write an {:?} buffer ({}); ask `buffer_id` for a read-only one",
                    rec.ty,
                    rec.type_name()
                ),
            });
        }
        Ok(())
    }

    fn expect_kind(&self, p: ProgramId, expected: ProgramKind, slot: String) -> Result<()> {
        let desc = self.scene.program(p)?.desc;
        if desc.kind != expected {
            return Err(RtError::WrongProgramKind {
                program: desc.name,
                location: desc.location(),
                found: desc.kind,
                expected,
                slot,
            });
        }
        Ok(())
    }

    fn entry_mut(&mut self, entry: u32) -> Result<&mut EntryPoint> {
        let count = self.scene.entry_points.len() as u32;
        self.scene.entry_points.get_mut(entry as usize).ok_or(RtError::NoSuchEntryPoint { entry, count })
    }

    fn check_ray_type(&self, ray_type: u32) -> Result<()> {
        if ray_type >= self.ray_type_count() {
            return Err(RtError::NoSuchRayType { ray_type, count: self.ray_type_count() });
        }
        Ok(())
    }

    pub fn set_ray_generation_program(&mut self, entry: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.expect_kind(p, ProgramKind::RayGeneration, format!("entry point {entry}'s ray generation"))?;
        self.entry_mut(entry)?.ray_generation = Some(p);
        Ok(())
    }

    /// Sets entry point `entry`'s exception program: it runs at a launch
    /// index after the index's first exception, with the code in
    /// `exception_code()`. Every exception is also recorded in
    /// [`LaunchReport::exceptions`], with or without an exception program.
    ///
    /// Without one, the default exception program runs (both backends): if
    /// the ray-generation program declares a `RwBuffer2d<Vec4>` variable
    /// (the first one, when it declares several), magenta `(1, 0, 1, 1)` is
    /// written into it at the launch index (skipped if the index is outside
    /// the buffer), so failing pixels stand out in the image.
    pub fn set_exception_program(&mut self, entry: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.expect_kind(p, ProgramKind::Exception, format!("entry point {entry}'s exception"))?;
        self.entry_mut(entry)?.exception = Some(p);
        Ok(())
    }

    pub fn set_miss_program(&mut self, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::Miss, format!("ray type {ray_type}'s miss"))?;
        self.scene.miss[ray_type as usize] = Some(p);
        Ok(())
    }

    // ---- geometry ----

    /// Creates a triangle geometry; the mesh is checked first.
    pub fn create_triangles(&mut self, mesh: TriangleMesh) -> Result<GeometryId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        let id = self.scene.geometries.len() as u32;
        mesh.validate().map_err(|problem| RtError::BadGeometry { geometry: id, problem })?;
        self.scene.geometries.push(GeometryRec {
            kind: GeometryKind::Triangles(mesh),
            vars: VarScope::default(),
            vertex_motion: None,
        });
        Ok(GeometryId(id))
    }

    /// Creates custom geometry of `primitive_count` primitives, each
    /// intersected by `intersection` and bounded by `bounding_box`.
    pub fn create_custom_geometry(
        &mut self,
        primitive_count: u32,
        intersection: ProgramId,
        bounding_box: ProgramId,
    ) -> Result<GeometryId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.expect_kind(intersection, ProgramKind::Intersection, "a custom geometry's intersection".into())?;
        self.expect_kind(bounding_box, ProgramKind::BoundingBox, "a custom geometry's bounding box".into())?;
        self.scene.geometries.push(GeometryRec {
            kind: GeometryKind::Custom { primitive_count, intersection, bounding_box },
            vars: VarScope::default(),
            vertex_motion: None,
        });
        Ok(GeometryId(self.scene.geometries.len() as u32 - 1))
    }

    /// Moves a triangle geometry's vertices (same count): accelerations over
    /// it are refit, not rebuilt, at the next launch. A geometry with vertex
    /// motion ([`set_motion_vertices`](Self::set_motion_vertices)) becomes
    /// static at these positions.
    pub fn set_triangle_positions(&mut self, g: GeometryId, positions: Vec<glam::Vec3>) -> Result<()> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        let (mesh, motion) = self.triangles_mut(g, "")?;
        if positions.len() != mesh.positions.len() {
            return Err(RtError::BadGeometry {
                geometry: g.0,
                problem: format!(
                    "{} positions given for {} vertices; create a new geometry to change topology",
                    positions.len(),
                    mesh.positions.len()
                ),
            });
        }
        // The rest of the mesh was checked when it was created; with the
        // same vertex count, only the positions themselves can be wrong.
        check_positions(&positions).map_err(|problem| RtError::BadGeometry { geometry: g.0, problem })?;
        mesh.positions = positions;
        *motion = None;
        self.accels.geometry_moved(g.0);
        Ok(())
    }

    /// Gives triangle geometry `g` vertex motion: `keys` are two or more
    /// sets of vertex positions (the mesh's vertex count each, its indices
    /// over them) spread evenly over `[t0, t1]`. A ray traced at time `t`
    /// (`rt_trace_at`) meets each triangle with its vertices interpolated
    /// linearly between the two keys around `t`, clamped to the first and
    /// last key outside the range (OptiX's `RT_MOTIONBORDERMODE_CLAMP`).
    /// The built-in attributes (`geometric_normal`, `barycentrics`) are the
    /// interpolated triangle's; shading normals and texture coordinates stay
    /// per vertex. The mesh's positions become the first key's, and
    /// [`set_triangle_positions`](Self::set_triangle_positions) makes it
    /// static again.
    ///
    /// Triangles' boxes hold every key, so no instant's hit is lost. The
    /// ray-query traversal does not interpolate vertices: a scene with
    /// vertex motion runs on the compute traversal.
    #[doc(alias = "rtGeometryTrianglesSetMotionVertices")]
    #[doc(alias = "rtGeometryTrianglesSetMotionSteps")]
    #[doc(alias = "rtGeometryTrianglesSetMotionRange")]
    #[doc(alias = "rtGeometryTrianglesSetMotionBorderMode")]
    pub fn set_motion_vertices(&mut self, g: GeometryId, keys: Vec<Vec<glam::Vec3>>, t0: f32, t1: f32) -> Result<()> {
        let (mesh, held) = self.triangles_mut(g, ": vertex motion keys move triangles' vertices")?;
        let motion = VertexMotion::new(keys, t0, t1, mesh.positions.len())
            .map_err(|problem| RtError::BadGeometry { geometry: g.0, problem })?;
        mesh.positions.clone_from(&motion.keys[0]);
        *held = Some(Box::new(motion));
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        self.accels.geometry_moved(g.0);
        Ok(())
    }

    /// Triangle geometry `g`'s mesh and vertex motion, to move its
    /// vertices; other geometry is refused as "not a triangle geometry"
    /// followed by `why`.
    fn triangles_mut(
        &mut self,
        g: GeometryId,
        why: &str,
    ) -> Result<(&mut TriangleMesh, &mut Option<Box<VertexMotion>>)> {
        let rec =
            self.scene.geometries.get_mut(g.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{g:?}")))?;
        match rec {
            GeometryRec { kind: GeometryKind::Triangles(mesh), vertex_motion, .. } => Ok((mesh, vertex_motion)),
            _ => Err(RtError::BadGeometry { geometry: g.0, problem: format!("not a triangle geometry{why}") }),
        }
    }

    /// Triangle geometry `g`'s vertex motion, if it has some.
    pub fn motion_vertices(&self, g: GeometryId) -> Option<&VertexMotion> {
        self.scene.geometries.get(g.0 as usize)?.vertex_motion.as_deref()
    }

    pub fn create_material(&mut self) -> MaterialId {
        self.scene.structure_version += 1;
        let n = self.ray_type_count() as usize;
        self.scene.materials.push(MaterialRec {
            closest_hit: vec![None; n],
            any_hit: vec![None; n],
            vars: VarScope::default(),
        });
        MaterialId(self.scene.materials.len() as u32 - 1)
    }

    fn material_mut(&mut self, m: MaterialId) -> Result<&mut MaterialRec> {
        self.scene.materials.get_mut(m.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{m:?}")))
    }

    pub fn set_closest_hit_program(&mut self, m: MaterialId, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::ClosestHit, format!("ray type {ray_type}'s closest hit"))?;
        self.material_mut(m)?.closest_hit[ray_type as usize] = Some(p);
        Ok(())
    }

    pub fn set_any_hit_program(&mut self, m: MaterialId, ray_type: u32, p: ProgramId) -> Result<()> {
        self.scene.structure_version += 1;
        self.check_ray_type(ray_type)?;
        self.expect_kind(p, ProgramKind::AnyHit, format!("ray type {ray_type}'s any hit"))?;
        self.material_mut(m)?.any_hit[ray_type as usize] = Some(p);
        Ok(())
    }

    pub fn create_geometry_instance(&mut self, g: GeometryId, materials: &[MaterialId]) -> Result<GeometryInstanceId> {
        self.scene.geometry_version += 1;
        self.scene.structure_version += 1;
        if g.0 as usize >= self.scene.geometries.len() {
            return Err(RtError::InvalidHandle(format!("{g:?}")));
        }
        if let Some(m) = materials.iter().find(|m| m.0 as usize >= self.scene.materials.len()) {
            return Err(RtError::InvalidHandle(format!("{m:?}")));
        }
        if materials.is_empty() {
            return Err(RtError::BadGeometry {
                geometry: g.0,
                problem: "a geometry instance needs at least one material".into(),
            });
        }
        self.scene.instances.push(GeometryInstanceRec {
            geometry: g,
            materials: materials.to_vec(),
            vars: VarScope::default(),
            instance_id: rt_abi::INSTANCE_ID_NONE,
        });
        Ok(GeometryInstanceId(self.scene.instances.len() as u32 - 1))
    }

    fn push_node(&mut self, kind: NodeKind) -> NodeId {
        self.scene.structure_version += 1;
        self.scene.nodes.push(NodeRec {
            kind,
            visibility_mask: 0xff,
            vars: VarScope::default(),
            instance_id: rt_abi::INSTANCE_ID_NONE,
        });
        NodeId(self.scene.nodes.len() as u32 - 1)
    }

    fn check_nodes(&self, nodes: &[NodeId]) -> Result<()> {
        match nodes.iter().find(|n| n.0 as usize >= self.scene.nodes.len()) {
            Some(n) => Err(RtError::InvalidHandle(format!("{n:?}"))),
            None => Ok(()),
        }
    }

    pub fn create_geometry_group(&mut self, children: &[GeometryInstanceId], accel: Acceleration) -> Result<NodeId> {
        self.scene.structure_version += 1;
        self.scene.geometry_version += 1;
        if let Some(c) = children.iter().find(|c| c.0 as usize >= self.scene.instances.len()) {
            return Err(RtError::InvalidHandle(format!("{c:?}")));
        }
        Ok(self.push_node(NodeKind::GeometryGroup { children: children.to_vec(), accel }))
    }

    pub fn create_group(&mut self, children: &[NodeId], accel: Acceleration) -> Result<NodeId> {
        self.check_nodes(children)?;
        Ok(self.push_node(NodeKind::Group { children: children.to_vec(), accel }))
    }

    /// A transform node; its inverse is computed here.
    pub fn create_transform(&mut self, matrix: Mat4, child: NodeId) -> Result<NodeId> {
        self.check_nodes(&[child])?;
        let inverse = checked_inverse(matrix)?;
        Ok(self.push_node(NodeKind::Transform { matrix, inverse, child, motion: None }))
    }

    /// A motion transform node: `keys` (two or more) spread evenly over the
    /// time range `[t0, t1]`, the transform at a ray's time
    /// ([`rt_trace_at`](rt_std::rt_trace_at)) interpolated between the two
    /// keys around it (matrices element by element, [`Srt`](crate::Srt)
    /// keys with their rotations slerped), clamped to the first and last
    /// key outside the range (OptiX's `RT_MOTIONBORDERMODE_CLAMP`, its
    /// default). Groups above bound the child over the whole motion
    /// ([`MotionTransform::bounds`](crate::MotionTransform)). An instant at
    /// which the interpolated matrix is singular hides the child.
    ///
    /// The ray-query traversal does not walk motion transforms: a scene
    /// with one runs on the compute traversal.
    #[doc(alias = "rtTransformSetMotionKeys")]
    #[doc(alias = "rtTransformSetMotionRange")]
    #[doc(alias = "rtTransformSetMotionBorderMode")]
    pub fn create_motion_transform(&mut self, keys: MotionKeys, t0: f32, t1: f32, child: NodeId) -> Result<NodeId> {
        self.check_nodes(&[child])?;
        let node = NodeId(self.scene.nodes.len() as u32);
        let motion = motion_keys(node, keys, t0, t1)?;
        let (matrix, inverse) = first_key(&motion);
        Ok(self.push_node(NodeKind::Transform { matrix, inverse, child, motion: Some(Box::new(motion)) }))
    }

    /// Gives transform `node` motion keys (as
    /// [`create_motion_transform`](Self::create_motion_transform));
    /// [`set_transform`](Self::set_transform) makes it static again.
    #[doc(alias = "rtTransformSetMotionKeys")]
    pub fn set_motion_keys(&mut self, node: NodeId, keys: MotionKeys, t0: f32, t1: f32) -> Result<()> {
        let motion = motion_keys(node, keys, t0, t1)?;
        self.scene.structure_version += 1;
        match self.scene.nodes.get_mut(node.0 as usize).map(|n| &mut n.kind) {
            Some(NodeKind::Transform { matrix, inverse, motion: m, .. }) => {
                (*matrix, *inverse) = first_key(&motion);
                *m = Some(Box::new(motion));
                self.accels.transform_moved();
                Ok(())
            }
            _ => Err(RtError::InvalidHandle(format!("{node:?} (not a transform)"))),
        }
    }

    /// Transform `node`'s motion, if it has one.
    pub fn motion_keys(&self, node: NodeId) -> Option<&MotionTransform> {
        match self.scene.nodes.get(node.0 as usize).map(|n| &n.kind) {
            Some(NodeKind::Transform { motion, .. }) => motion.as_deref(),
            _ => None,
        }
    }

    /// Changes a transform's matrix (a refit of the groups above it).
    pub fn set_transform(&mut self, node: NodeId, matrix: Mat4) -> Result<()> {
        self.scene.structure_version += 1;
        let inv = checked_inverse(matrix)?;
        match self.scene.nodes.get_mut(node.0 as usize).map(|n| &mut n.kind) {
            Some(NodeKind::Transform { matrix: m, inverse, motion, .. }) => {
                *m = matrix;
                *inverse = inv;
                *motion = None;
                self.accels.transform_moved();
                Ok(())
            }
            _ => Err(RtError::InvalidHandle(format!("{node:?} (not a transform)"))),
        }
    }

    pub fn create_selector(&mut self, visit: ProgramId, children: &[NodeId]) -> Result<NodeId> {
        self.expect_kind(visit, ProgramKind::Visit, "a selector's visit".into())?;
        self.check_nodes(children)?;
        Ok(self.push_node(NodeKind::Selector { visit, children: children.to_vec() }))
    }

    /// Rays trace into `node` only if their mask shares a bit with this.
    pub fn set_visibility_mask(&mut self, node: NodeId, mask: u8) -> Result<()> {
        self.scene.structure_version += 1;
        let n = self.scene.nodes.get_mut(node.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{node:?}")))?;
        n.visibility_mask = mask;
        Ok(())
    }

    /// Gives the instances below `target` the id `instance_id()` returns
    /// on their hits (OptiX 7's `OptixInstance::instanceId`): `target` is a
    /// geometry instance, or a transform (every geometry instance below it).
    /// A hit's id is its geometry instance's own, else that of the
    /// innermost transform with one on the traced path, else
    /// [`INSTANCE_ID_NONE`](rt_std::INSTANCE_ID_NONE), which also clears an
    /// id. See [`rt_std::instance_index`] for what an instance is.
    #[doc(alias = "instanceId")]
    pub fn set_instance_id(&mut self, target: impl Into<Scope>, id: u32) -> Result<()> {
        let target = target.into();
        let slot = match target {
            Scope::GeometryInstance(gi) => self.scene.instances.get_mut(gi.0 as usize).map(|g| &mut g.instance_id),
            Scope::Node(n) => match self.scene.nodes.get_mut(n.0 as usize) {
                Some(rec @ NodeRec { kind: NodeKind::Transform { .. }, .. }) => Some(&mut rec.instance_id),
                Some(_) => {
                    return Err(RtError::InvalidHandle(format!(
                        "{n:?} (not a transform: instance ids are set on geometry instances and transforms)"
                    )));
                }
                None => None,
            },
            _ => {
                return Err(RtError::InvalidHandle(format!(
                    "{target:?} (instance ids are set on geometry instances and transforms)"
                )));
            }
        };
        *slot.ok_or_else(|| RtError::InvalidHandle(format!("{target:?}")))? = id;
        self.scene.structure_version += 1;
        Ok(())
    }

    /// The id set on a geometry instance or transform
    /// ([`set_instance_id`](Self::set_instance_id);
    /// [`INSTANCE_ID_NONE`](rt_std::INSTANCE_ID_NONE) when none is).
    pub fn instance_id(&self, target: impl Into<Scope>) -> Result<u32> {
        let target = target.into();
        let id = match target {
            Scope::GeometryInstance(gi) => self.scene.instances.get(gi.0 as usize).map(|g| g.instance_id),
            Scope::Node(n) => self.scene.nodes.get(n.0 as usize).map(|r| r.instance_id),
            _ => None,
        };
        id.ok_or_else(|| RtError::InvalidHandle(format!("{target:?}")))
    }

    // ---- variables ----

    /// Sets variable `name` on `scope`. Values are plain data (`f32`,
    /// `Vec3`, `#[rt_struct]`s), buffers, samplers or nodes. Changing a value
    /// never relinks.
    pub fn set_var(&mut self, scope: impl Into<Scope>, name: &str, value: impl IntoVariable) -> Result<()> {
        let value = value.into_variable();
        self.scene.scope_mut(scope.into())?.set(name, value);
        Ok(())
    }

    /// Removes variable `name` from `scope`; returns whether it was set.
    pub fn remove_var(&mut self, scope: impl Into<Scope>, name: &str) -> Result<bool> {
        Ok(self.scene.scope_mut(scope.into())?.remove(name).is_some())
    }

    // ---- buffers and samplers ----

    /// A 1D buffer holding `data`.
    pub fn create_buffer<T: RtData + Send + Sync>(&mut self, ty: BufferType, data: Vec<T>) -> BufferId {
        let len = data.len() as u32;
        self.scene.buffers.push(BufferRec::new(Box::new(Typed::new(data)), ty, [len, 1, 1], 1));
        BufferId(self.scene.buffers.len() as u32 - 1)
    }

    /// A 2D buffer of `width` x `height` zeroed elements.
    pub fn create_buffer_2d<T: RtData + Send + Sync>(
        &mut self,
        ty: BufferType,
        width: u32,
        height: u32,
    ) -> Result<BufferId> {
        let n = (width as u64) * (height as u64);
        if n > (u32::MAX as u64) {
            return Err(RtError::BadBuffer {
                buffer: self.scene.buffers.len() as u32,
                problem: format!("{width}x{height} elements do not fit in 32-bit indices"),
            });
        }
        let zero = T::read_words(&vec![0u32; T::LAYOUT.words as usize]);
        self.scene.buffers.push(BufferRec::new(
            Box::new(Typed::new(vec![zero; n as usize])),
            ty,
            [width, height, 1],
            2,
        ));
        Ok(BufferId(self.scene.buffers.len() as u32 - 1))
    }

    /// A 3D buffer (OptiX's `rtBuffer<T, 3>`, programs' `Buffer3d<T>` and
    /// `RwBuffer3d<T>`) of `width` x `height` x `depth` zeroed elements,
    /// stored as `depth` slices of `height` rows: element `(x, y, z)` is
    /// element `x + (y + z * height) * width` of [`read_buffer`](Self::read_buffer)
    /// and [`write_buffer`](Self::write_buffer).
    #[doc(alias = "rtBufferSetSize3D")]
    pub fn create_buffer_3d<T: RtData + Send + Sync>(
        &mut self,
        ty: BufferType,
        width: u32,
        height: u32,
        depth: u32,
    ) -> Result<BufferId> {
        let n = (width as u64) * (height as u64) * (depth as u64);
        if n > (u32::MAX as u64) {
            return Err(RtError::BadBuffer {
                buffer: self.scene.buffers.len() as u32,
                problem: format!("{width}x{height}x{depth} elements do not fit in 32-bit indices"),
            });
        }
        let zero = T::read_words(&vec![0u32; T::LAYOUT.words as usize]);
        let storage = Box::new(Typed::new(vec![zero; n as usize]));
        self.scene.buffers.push(BufferRec::new(storage, ty, [width, height, depth], 3));
        Ok(BufferId(self.scene.buffers.len() as u32 - 1))
    }

    fn typed<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<&Typed<T>> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{b:?}")))?;
        rec.storage.as_any().downcast_ref::<Typed<T>>().ok_or_else(|| RtError::BadBuffer {
            buffer: b.0,
            problem: format!("holds `{}`, not `{}`", rec.storage.layout().rust, T::LAYOUT.rust),
        })
    }

    /// Reads a buffer's elements back (row-major for 2D buffers). A
    /// device-local buffer ([`Context::set_buffer_device_local`]) that a
    /// wgpu launch wrote is read from the device.
    pub fn read_buffer<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<Vec<T>> {
        backend::waiting::block(self.read_buffer_async(b))
    }

    /// [`Context::read_buffer`] for a caller that must not block (a
    /// browser page): a device-local buffer
    /// ([`Context::set_buffer_device_local`]) is read from the device,
    /// awaited; any other buffer is the host's copy, as always.
    pub async fn read_buffer_async<T: RtData + Send + Sync>(&self, b: BufferId) -> Result<Vec<T>> {
        let typed = self.typed::<T>(b)?;
        match self.device_words_async(b).await {
            Some(words) => {
                let w = T::LAYOUT.words as usize;
                Ok(words?.chunks_exact(w).take(typed.len()).map(T::read_words).collect())
            }
            None => Ok(typed.to_vec()),
        }
    }

    /// Overwrites a buffer's elements (same count). Never relinks.
    pub fn write_buffer<T: RtData + Send + Sync>(&mut self, b: BufferId, data: &[T]) -> Result<()> {
        let len = self.typed::<T>(b)?.len();
        if data.len() != len {
            return Err(RtError::BadBuffer {
                buffer: b.0,
                problem: format!("{} elements written to a buffer of {len}", data.len()),
            });
        }
        let rec = &mut self.scene.buffers[b.0 as usize];
        rec.storage.as_any_mut().downcast_mut::<Typed<T>>().expect("checked above").write(data);
        rec.host_version += 1;
        Ok(())
    }

    /// `(width, height)` of a buffer (height 1 for 1D buffers; a 3D
    /// buffer's depth: [`buffer_size_3d`](Self::buffer_size_3d)).
    pub fn buffer_size(&self, b: BufferId) -> Result<(u32, u32)> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{b:?}")))?;
        Ok((rec.width, rec.height))
    }

    /// `(width, height, depth)` of a buffer (depth 1 for 1D and 2D
    /// buffers).
    pub fn buffer_size_3d(&self, b: BufferId) -> Result<(u32, u32, u32)> {
        let rec = self.scene.buffers.get(b.0 as usize).ok_or_else(|| RtError::InvalidHandle(format!("{b:?}")))?;
        Ok((rec.width, rec.height, rec.depth))
    }

    /// A sampler over RGBA texels (row-major, `width * height` of them).
    pub fn create_sampler(
        &mut self,
        texels: Vec<Vec4>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        if texels.len() != width as usize * height as usize || texels.is_empty() {
            return Err(RtError::BadBuffer {
                buffer: self.scene.samplers.len() as u32,
                problem: format!("{} texels for a {width}x{height} texture", texels.len()),
            });
        }
        let rec = SamplerRec {
            texels: texels.into_boxed_slice(),
            width,
            height,
            levels: 1,
            modes: SamplerModes { wrap, filter, ..SamplerModes::default() },
            shape: SamplerShape::Flat,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A mipmapped sampler (OptiX's mip levels of an `RTtexturesampler`):
    /// `levels[0]` holds the `width * height` texels of level 0 (row-major),
    /// `levels[l]` those of level `l`, `max(1, width >> l)` by
    /// `max(1, height >> l)` texels ([`rt_std::mip_level_size`]); any number of levels
    /// from 1 to the full chain ([`rt_std::mip_level_count`], down to 1x1).
    /// `mip` says how [`Sampler2d::sample_lod`](rt_std::Sampler2d) and
    /// `sample_grad` combine levels. A level of the wrong texel count, or
    /// more levels than the chain has, is refused naming the sampler and
    /// the level.
    pub fn create_sampler_mipmapped(
        &mut self,
        levels: Vec<Vec<Vec4>>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let fail = |problem: String| RtError::BadSampler { sampler: self.scene.samplers.len() as u32, problem };
        let chain = rt_std::mip_level_count(width, height);
        if levels.is_empty() {
            return Err(fail(format!("no mip levels for a {width}x{height} texture (level 0 is needed)")));
        }
        if levels.len() > chain as usize {
            return Err(fail(format!(
                "{} mip levels for a {width}x{height} texture, whose full chain has {chain} (down to 1x1)",
                levels.len()
            )));
        }
        for (l, level) in levels.iter().enumerate() {
            let size = rt_std::mip_level_size(glam::UVec2::new(width, height), l as u32);
            if level.len() != size.x as usize * size.y as usize {
                return Err(fail(format!(
                    "mip level {l} has {} texels; level {l} of a {width}x{height} texture is {}x{} ({} texels)",
                    level.len(),
                    size.x,
                    size.y,
                    size.x as usize * size.y as usize
                )));
            }
        }
        let count = levels.len() as u32;
        let rec = SamplerRec {
            texels: levels.concat().into_boxed_slice(),
            width,
            height,
            levels: count,
            modes: SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates },
            shape: SamplerShape::Flat,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A sampler over texels of any supported format (OptiX's buffer
    /// formats, read and index modes): the host decodes them to RGBA `f32`
    /// on upload as [`TexelData::decode`](crate::TexelData::decode) says
    /// (the texture takes 16 bytes a texel), `width * height` of them,
    /// row-major, one level. With [`IndexMode::ArrayIndex`] coordinates are
    /// in texels and, as GPUs' unnormalised coordinates, clamp to the edge:
    /// another wrap mode is refused. Errors name the sampler.
    pub fn create_sampler_from_texels(
        &mut self,
        texels: crate::TexelData,
        width: u32,
        height: u32,
        options: crate::SamplerOptions,
    ) -> Result<SamplerId> {
        let fail = |problem: String| RtError::BadSampler { sampler: self.scene.samplers.len() as u32, problem };
        if texels.len() != width as usize * height as usize || texels.is_empty() {
            return Err(fail(format!(
                "{} {} texels for a {width}x{height} texture",
                texels.len(),
                texels.format_name()
            )));
        }
        if options.index == IndexMode::ArrayIndex && options.wrap != WrapMode::Clamp {
            return Err(fail(format!(
                "array-index coordinates (RT_TEXTURE_INDEX_ARRAY_INDEX) clamp to the edge, as GPUs' unnormalised coordinates do: use WrapMode::Clamp, not {:?}",
                options.wrap
            )));
        }
        let rec = SamplerRec {
            texels: texels.decode(options.read).into_boxed_slice(),
            width,
            height,
            levels: 1,
            modes: SamplerModes {
                wrap: options.wrap,
                filter: options.filter,
                mip: MipFilter::Linear,
                index: options.index,
            },
            shape: SamplerShape::Flat,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A 3D sampler over texels of any supported format (OptiX's buffer
    /// formats and read modes behind a 3D sampler): the host decodes them
    /// to RGBA `f32` on upload as [`TexelData::decode`](crate::TexelData::decode)
    /// says, `size` of them (texel `(x, y, z)` at
    /// `x + y * width + z * width * height`), one level (for levels, decode
    /// them and pass them to
    /// [`create_sampler_3d_mipmapped`](Self::create_sampler_3d_mipmapped)).
    /// With [`IndexMode::ArrayIndex`] coordinates are in texels and clamp to
    /// the edge, as [`create_sampler_from_texels`](Self::create_sampler_from_texels)'s:
    /// another wrap mode is refused, as is the wrong texel count, naming
    /// the sampler.
    pub fn create_sampler_3d_from_texels(
        &mut self,
        texels: crate::TexelData,
        size: glam::UVec3,
        options: crate::SamplerOptions,
    ) -> Result<SamplerId> {
        let fail = |problem: String| RtError::BadSampler { sampler: self.scene.samplers.len() as u32, problem };
        let count = size.x as u64 * size.y as u64 * size.z as u64;
        if texels.len() as u64 != count || texels.is_empty() {
            return Err(fail(format!(
                "{} {} texels for a {}x{}x{} texture",
                texels.len(),
                texels.format_name(),
                size.x,
                size.y,
                size.z
            )));
        }
        if options.index == IndexMode::ArrayIndex && options.wrap != WrapMode::Clamp {
            return Err(fail(format!(
                "array-index coordinates (RT_TEXTURE_INDEX_ARRAY_INDEX) clamp to the edge, as GPUs' unnormalised coordinates do: use WrapMode::Clamp, not {:?}",
                options.wrap
            )));
        }
        let id = self.create_sampler_3d(texels.decode(options.read), size, options.wrap, options.filter)?;
        self.scene.samplers[id.0 as usize].modes.index = options.index;
        Ok(id)
    }

    /// A cube map over faces of any supported format, decoded to RGBA
    /// `f32` on upload as [`TexelData::decode`](crate::TexelData::decode)
    /// says with read mode `read`: `faces[0..6]` (+x, -x, +y, -y, +z, -z)
    /// of `size * size` texels each, one level (for levels, decode them
    /// and pass them to
    /// [`create_sampler_cube_mipmapped`](Self::create_sampler_cube_mipmapped)).
    /// A face of the wrong texel count is refused naming the sampler, the
    /// face and its format.
    pub fn create_sampler_cube_from_texels(
        &mut self,
        faces: [crate::TexelData; 6],
        size: u32,
        filter: FilterMode,
        read: crate::ReadMode,
    ) -> Result<SamplerId> {
        const NAMES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];
        let n = size as usize * size as usize;
        for (face, name) in faces.iter().zip(NAMES) {
            if face.len() != n || n == 0 {
                return Err(RtError::BadSampler {
                    sampler: self.scene.samplers.len() as u32,
                    problem: format!(
                        "cube face {name} has {} {} texels for a {size}x{size} face",
                        face.len(),
                        face.format_name()
                    ),
                });
            }
        }
        self.create_sampler_cube(faces.map(|f| f.decode(read)), size, filter)
    }

    /// A 3D sampler (OptiX `rtTextureSampler<float4, 3>`, read by a
    /// program's `Sampler3d` variable) over `width * height * depth` RGBA
    /// texels, texel `(x, y, z)` at `x + y * width + z * width * height`;
    /// one level. The wrong texel count is refused naming the sampler.
    pub fn create_sampler_3d(
        &mut self,
        texels: Vec<Vec4>,
        size: glam::UVec3,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let count = size.x as u64 * size.y as u64 * size.z as u64;
        if texels.len() as u64 != count || texels.is_empty() {
            return Err(RtError::BadSampler {
                sampler: self.scene.samplers.len() as u32,
                problem: format!("{} texels for a {}x{}x{} texture", texels.len(), size.x, size.y, size.z),
            });
        }
        let rec = SamplerRec {
            texels: texels.into_boxed_slice(),
            width: size.x,
            height: size.y,
            levels: 1,
            modes: SamplerModes { wrap, filter, ..SamplerModes::default() },
            shape: SamplerShape::Volume(size.z),
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A cube map (OptiX's cube-map textures, read by a program's
    /// `SamplerCube` variable with `sample_dir`): six `size x size` faces
    /// of RGBA texels, `faces[0..6]` being +x, -x, +y, -y, +z, -z (Vulkan's
    /// layer order), each row-major as Vulkan lays a face out (`s` along a
    /// row, `t` down the rows; see `SamplerCube::face_coordinates`). Faces
    /// clamp to their edges. A face of the wrong texel count is refused
    /// naming the sampler and the face.
    pub fn create_sampler_cube(&mut self, faces: [Vec<Vec4>; 6], size: u32, filter: FilterMode) -> Result<SamplerId> {
        const NAMES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];
        let n = size as usize * size as usize;
        for (face, name) in faces.iter().zip(NAMES) {
            if face.len() != n || n == 0 {
                return Err(RtError::BadSampler {
                    sampler: self.scene.samplers.len() as u32,
                    problem: format!("cube face {name} has {} texels for a {size}x{size} face", face.len()),
                });
            }
        }
        let rec = SamplerRec {
            texels: faces.concat().into_boxed_slice(),
            width: size,
            height: size,
            levels: 1,
            modes: SamplerModes { wrap: WrapMode::Clamp, filter, ..SamplerModes::default() },
            shape: SamplerShape::Cube,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A mipmapped 3D sampler (OptiX's mip levels of a 3D
    /// `RTtexturesampler`, read by `Sampler3d::sample_lod`): `levels[0]`
    /// holds level 0's `size` texels (texel `(x, y, z)` at
    /// `x + y * width + z * width * height`), `levels[l]` those of level
    /// `l`, [`rt_std::mip_level_size_3d`]; from 1 level to the full chain
    /// ([`rt_std::mip_level_count_3d`], down to 1x1x1). A level of the
    /// wrong texel count, or more levels than the chain has, is refused
    /// naming the sampler and the level.
    pub fn create_sampler_3d_mipmapped(
        &mut self,
        levels: Vec<Vec<Vec4>>,
        size: glam::UVec3,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let fail = |problem: String| RtError::BadSampler { sampler: self.scene.samplers.len() as u32, problem };
        let name = format!("{}x{}x{}", size.x, size.y, size.z);
        let chain = rt_std::mip_level_count_3d(size);
        if levels.is_empty() || size.min_element() == 0 {
            return Err(fail(format!("no mip levels for a {name} texture (level 0 is needed, not empty)")));
        }
        if levels.len() > chain as usize {
            return Err(fail(format!(
                "{} mip levels for a {name} texture, whose full chain has {chain} (down to 1x1x1)",
                levels.len()
            )));
        }
        for (l, level) in levels.iter().enumerate() {
            let s = rt_std::mip_level_size_3d(size, l as u32);
            let n = s.x as usize * s.y as usize * s.z as usize;
            if level.len() != n {
                return Err(fail(format!(
                    "mip level {l} has {} texels; level {l} of a {name} texture is {}x{}x{} ({n} texels)",
                    level.len(),
                    s.x,
                    s.y,
                    s.z
                )));
            }
        }
        let rec = SamplerRec {
            levels: levels.len() as u32,
            texels: levels.concat().into_boxed_slice(),
            width: size.x,
            height: size.y,
            modes: SamplerModes { wrap, filter, mip, index: IndexMode::NormalizedCoordinates },
            shape: SamplerShape::Volume(size.z),
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A mipmapped 3D sampler whose levels are generated on the host: the
    /// full chain of [`generate_mip_levels_3d`](crate::generate_mip_levels_3d)
    /// (a 2x2x2 box filter, down to 1x1x1) over level 0's texels.
    pub fn create_sampler_3d_with_mips(
        &mut self,
        texels: Vec<Vec4>,
        size: glam::UVec3,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let levels = crate::buffer::generate_mip_levels_3d(&texels, size);
        if levels.is_empty() {
            return Err(RtError::BadSampler {
                sampler: self.scene.samplers.len() as u32,
                problem: format!("{} texels for a {}x{}x{} texture", texels.len(), size.x, size.y, size.z),
            });
        }
        self.create_sampler_3d_mipmapped(levels, size, wrap, filter, mip)
    }

    /// A mipmapped cube map (read by `SamplerCube::sample_dir_lod`):
    /// `levels[l]` holds level `l`'s six faces (+x, -x, +y, -y, +z, -z, as
    /// [`create_sampler_cube`](Self::create_sampler_cube) has them) of side
    /// `max(1, size >> l)`; from 1 level to the full chain (down to 1x1
    /// faces). A face of the wrong texel count, or more levels than the
    /// chain has, is refused naming the sampler, the level and the face.
    pub fn create_sampler_cube_mipmapped(
        &mut self,
        levels: Vec<[Vec<Vec4>; 6]>,
        size: u32,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        const NAMES: [&str; 6] = ["+x", "-x", "+y", "-y", "+z", "-z"];
        let fail = |problem: String| RtError::BadSampler { sampler: self.scene.samplers.len() as u32, problem };
        let chain = rt_std::mip_level_count(size, size);
        if levels.is_empty() || size == 0 {
            return Err(fail(format!("no mip levels for a cube map of {size}x{size} faces (level 0 is needed)")));
        }
        if levels.len() > chain as usize {
            return Err(fail(format!(
                "{} mip levels for a cube map of {size}x{size} faces, whose full chain has {chain} (down to 1x1)",
                levels.len()
            )));
        }
        for (l, faces) in levels.iter().enumerate() {
            let side = (size >> l).max(1) as usize;
            for (face, name) in faces.iter().zip(NAMES) {
                if face.len() != side * side {
                    return Err(fail(format!(
                        "cube face {name} of mip level {l} has {} texels for a {side}x{side} face",
                        face.len()
                    )));
                }
            }
        }
        let rec = SamplerRec {
            levels: levels.len() as u32,
            texels: levels.iter().flat_map(|faces| faces.concat()).collect(),
            width: size,
            height: size,
            modes: SamplerModes { wrap: WrapMode::Clamp, filter, mip, ..SamplerModes::default() },
            shape: SamplerShape::Cube,
        };
        self.scene.samplers.push(rec);
        Ok(SamplerId(self.scene.samplers.len() as u32 - 1))
    }

    /// A mipmapped cube map whose levels are generated on the host: each
    /// face's full chain of [`generate_mip_levels`](crate::generate_mip_levels)
    /// (a 2x2 box filter within the face, down to 1x1).
    pub fn create_sampler_cube_with_mips(
        &mut self,
        faces: [Vec<Vec4>; 6],
        size: u32,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        let lens = faces.each_ref().map(Vec::len);
        let chains = faces.map(|f| crate::buffer::generate_mip_levels(&f, size, size));
        let count = chains.iter().map(Vec::len).min().unwrap_or(0);
        if count == 0 {
            return Err(RtError::BadSampler {
                sampler: self.scene.samplers.len() as u32,
                problem: format!("cube faces of {lens:?} texels (+x to -z) for {size}x{size} faces"),
            });
        }
        let mut chains = chains.map(Vec::into_iter);
        let levels = (0..count).map(|_| std::array::from_fn(|f| chains[f].next().unwrap_or_default())).collect();
        self.create_sampler_cube_mipmapped(levels, size, filter, mip)
    }

    /// A mipmapped sampler whose levels are generated on the host: the full
    /// chain of [`generate_mip_levels`](crate::generate_mip_levels) (a 2x2
    /// box filter, down to 1x1) over level 0's `width * height` texels.
    pub fn create_sampler_with_mips(
        &mut self,
        texels: Vec<Vec4>,
        width: u32,
        height: u32,
        wrap: WrapMode,
        filter: FilterMode,
        mip: MipFilter,
    ) -> Result<SamplerId> {
        if texels.len() != width as usize * height as usize || texels.is_empty() {
            return Err(RtError::BadSampler {
                sampler: self.scene.samplers.len() as u32,
                problem: format!("{} texels for a {width}x{height} texture", texels.len()),
            });
        }
        let levels = crate::buffer::generate_mip_levels(&texels, width, height);
        self.create_sampler_mipmapped(levels, width, height, wrap, filter, mip)
    }

    /// A sampler from an image (8-bit channels map to `[0, 1]`, float
    /// channels are kept as they are).
    pub fn create_sampler_from_image(
        &mut self,
        image: &image::DynamicImage,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let rgba = image.to_rgba32f();
        let (w, h) = rgba.dimensions();
        let texels = rgba.pixels().map(|p| Vec4::from_array(p.0)).collect();
        self.create_sampler(texels, w, h, wrap, filter)
    }

    /// A sampler from an image file (PNG or Radiance HDR, by content). A
    /// file of another format, or one that does not decode, is refused with
    /// the path and the reason.
    pub fn create_sampler_from_file(
        &mut self,
        path: impl AsRef<std::path::Path>,
        wrap: WrapMode,
        filter: FilterMode,
    ) -> Result<SamplerId> {
        let path = path.as_ref();
        let fail = |problem: String| RtError::Texture { path: path.display().to_string(), problem };
        let reader = image::ImageReader::open(path)
            .map_err(|e| fail(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| fail(e.to_string()))?;
        let Some(format) = reader.format() else {
            return Err(fail("not an image format this build reads (PNG, Radiance HDR)".into()));
        };
        if !matches!(format, image::ImageFormat::Png | image::ImageFormat::Hdr) {
            return Err(fail(format!(
                "{} images are not supported (supported: PNG, Radiance HDR)",
                format.extensions_str().first().unwrap_or(&"this kind of").to_uppercase()
            )));
        }
        let image = reader.decode().map_err(|e| fail(format!("does not decode as {format:?}: {e}")))?;
        self.create_sampler_from_image(&image, wrap, filter)
    }

    // ---- launching ----

    /// Runs entry point `entry` over `width` x `height` launch indices, as
    /// tiles under the context's budget ([`Context::set_tile_budget`]).
    pub fn launch(&mut self, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), None, None)
    }

    /// [`Context::launch`] for a caller that must not block: a browser
    /// page (wasm32 over WebGPU), whose one thread cannot wait for the GPU,
    /// awaits it, and its device opens asynchronously too. Natively it is
    /// the same launch, and awaiting it (with any executor) blocks as
    /// [`Context::launch`] does. The blocking calls in a browser fail,
    /// saying to use this instead, where they would wait for the GPU.
    ///
    /// ```no_run
    /// # async fn f(ctx: &mut rt_runtime::Context, out: rt_runtime::BufferId) -> rt_runtime::Result<()> {
    /// let report = ctx.launch_async(0, 640, 480).await?;
    /// let pixels = ctx.read_buffer::<glam::Vec4>(out)?;
    /// # Ok(()) }
    /// ```
    pub async fn launch_async(&mut self, entry: u32, width: u32, height: u32) -> Result<LaunchReport> {
        self.run_launch_async((entry, width, height, 1), None, None).await
    }

    /// [`Context::launch`], calling `progress` after every tile with where
    /// the launch stands. Its answer may cancel the launch before the next
    /// tile ([`LaunchControl::Cancel`]): the launch then fails with
    /// [`RtError::LaunchCancelled`] and every buffer is as it was before
    /// it. A cancel after the last tile changes nothing: the launch is
    /// done. OptiX 6's `rtContextSetTimeoutCallback` asks the same
    /// question between the pieces of a launch.
    #[doc(alias = "rtContextSetTimeoutCallback")]
    pub fn launch_with_progress(
        &mut self,
        entry: u32,
        width: u32,
        height: u32,
        mut progress: impl FnMut(LaunchProgress) -> LaunchControl,
    ) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), None, Some(&mut progress))
    }

    /// Runs only `part` of a `width` x `height` launch of entry point
    /// `entry`: programs see the whole size as their launch dimensions and
    /// their own place in it as their launch index, so parts launched
    /// apart (on several machines: `render --tile K/N`) give, put
    /// together, what one launch gives. Indices outside the part do not
    /// run. The part must lie on the 8 x 8 grid of launch indices (its
    /// origin, and its far edges unless they are the launch's, multiples
    /// of 8); else the launch fails with [`RtError::BadLaunch`]. Tiles and
    /// progress are as [`Context::launch_with_progress`]'s, within the part.
    pub fn launch_part(
        &mut self,
        entry: u32,
        width: u32,
        height: u32,
        part: Tile,
        mut progress: impl FnMut(LaunchProgress) -> LaunchControl,
    ) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, 1), Some(part), Some(&mut progress))
    }

    /// Calls `report` after every launch, failed or not, with what it did:
    /// acceleration builds and refits, encodes, pipelines linked, bytes
    /// uploaded and the time of each phase ([`UsageReport`], whose
    /// `Display` is one line of text). `None` stops the reports.
    #[doc(alias = "rtContextSetUsageReportCallback")]
    pub fn set_usage_report(&mut self, report: Option<UsageCallback>) {
        self.usage_report = report;
    }

    /// Every blocking launch: [`Context::run_launch_async`] run to its end.
    fn run_launch(
        &mut self,
        size: (u32, u32, u32, u32),
        part: Option<Tile>,
        progress: Option<&mut dyn FnMut(LaunchProgress) -> LaunchControl>,
    ) -> Result<LaunchReport> {
        backend::waiting::block(self.run_launch_async(size, part, progress))
    }

    /// Every launch: the backend's run, then the usage report.
    async fn run_launch_async(
        &mut self,
        (entry, width, height, depth): (u32, u32, u32, u32),
        part: Option<Tile>,
        progress: Option<&mut dyn FnMut(LaunchProgress) -> LaunchControl>,
    ) -> Result<LaunchReport> {
        let before = self.usage_counters();
        // Device-local buffers another backend holds come to the host first.
        let settled = self.settle_device_buffers(Some(self.backend.kind()));
        let pacing = Pacing { part, pace: &mut self.pace, progress };
        let (scene, settings, accels) = (&mut self.scene, &self.settings, &mut self.accels);
        let result = match settled {
            Ok(()) => {
                let size = (entry, width, height, depth);
                backend::launch(&mut *self.backend, scene, settings, accels, size, pacing).await
            }
            Err(e) => Err(e),
        };
        if let Some(mut callback) = self.usage_report.take() {
            let after = self.usage_counters();
            let stats = self.backend.stats();
            let report = UsageReport {
                entry,
                size: glam::UVec2::new(width, height.saturating_mul(depth)),
                backend: self.backend.kind(),
                outcome: result.as_ref(),
                acceleration_builds: after[0] - before[0],
                acceleration_refits: after[1] - before[1],
                scene_encoded: after[2] > before[2],
                geometry_encoded: after[3] > before[3],
                pipelines_created: after[4] - before[4],
                upload_bytes: if self.backend.kind() == Backend::Wgpu && result.is_ok() { after[5] } else { 0 },
                traversal: stats.traversal.filter(|_| self.backend.kind() == Backend::Wgpu),
            };
            callback(&report);
            self.usage_report = Some(callback);
        }
        result
    }

    /// The counters a usage report takes the difference of: builds,
    /// refits, scene and geometry encodes, pipelines, the last upload.
    fn usage_counters(&self) -> [u64; 6] {
        let (builds, refits) = self.acceleration_builds();
        [
            builds,
            refits,
            self.scene_encodes(),
            self.geometry_encodes(),
            self.pipelines_created(),
            self.last_upload_bytes(),
        ]
    }

    /// How launches are cut into tiles, each one submission (see
    /// [`crate::backend::tiles`]): by default tiles sized to run in about a
    /// quarter second each ([`TileBudget::Time`] of
    /// [`DEFAULT_TILE_BUDGET`](crate::backend::tiles::DEFAULT_TILE_BUDGET)),
    /// well inside the two seconds after which desktop drivers reset a
    /// GPU. Results are the same whatever the cut.
    pub fn set_tile_budget(&mut self, budget: TileBudget) {
        self.settings.tile_budget = budget;
    }

    /// The budget set by [`Context::set_tile_budget`].
    pub fn tile_budget(&self) -> TileBudget {
        self.settings.tile_budget
    }

    /// A 1D launch of `width` indices.
    pub fn launch_1d(&mut self, entry: u32, width: u32) -> Result<LaunchReport> {
        self.launch(entry, width, 1)
    }

    /// A 3D launch of `width` x `height` x `depth` indices (OptiX's
    /// `rtContextLaunch3D`): programs read their index with
    /// `launch_index_3d()` and the size with `launch_dim_3d()`
    /// (`launch_index()` and `launch_dim()` give the first two axes). It
    /// runs as a 2D launch of `width` x `height * depth` indices, the
    /// slices' rows in turn, tiled as any launch; exception records, prints
    /// and the print filter ([`set_print`](Self::set_print)) name indices
    /// of that grid: `(x, y + z * height)`.
    #[doc(alias = "rtContextLaunch3D")]
    pub fn launch_3d(&mut self, entry: u32, width: u32, height: u32, depth: u32) -> Result<LaunchReport> {
        self.run_launch((entry, width, height, depth), None, None)
    }
}

/// Checked motion keys, or an error naming transform `node`.
fn motion_keys(node: NodeId, keys: MotionKeys, t0: f32, t1: f32) -> Result<MotionTransform> {
    MotionTransform::new(keys, t0, t1)
        .map_err(|problem| RtError::BadTransform { problem: format!("transform {}: {problem}", node.index()) })
}

/// The first key's matrix and its inverse (identity where it has none): what
/// the scene keeps as a motion transform's static matrix.
fn first_key(motion: &MotionTransform) -> (Mat4, Mat4) {
    let m = motion.matrix_at(motion.t0);
    (m, checked_inverse(m).unwrap_or(Mat4::IDENTITY))
}

fn checked_inverse(m: Mat4) -> Result<Mat4> {
    let det = m.determinant();
    if !det.is_finite() || det.abs() < 1e-12 || !m.is_finite() {
        return Err(RtError::BadTransform { problem: format!("the matrix is singular or not finite: {m:?}") });
    }
    Ok(m.inverse())
}

/// `fn(glam::f32::vec3::Vec3) -> glam::f32::vec3::Vec3` as
/// `fn(Vec3) -> Vec3`: every path cut to its last segment.
fn short_type_name(full: &str) -> String {
    let mut out = String::new();
    let mut word = String::new();
    for c in full.chars().chain(std::iter::once(' ')) {
        if c.is_alphanumeric() || c == '_' || c == ':' {
            word.push(c);
        } else {
            out.push_str(word.rsplit("::").next().unwrap_or(&word));
            word.clear();
            out.push(c);
        }
    }
    out.trim_end().to_string()
}
