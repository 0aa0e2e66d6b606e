//! The device and its health: the adapter opened (or the application's
//! device), its limits and the one bind-group layout, and what its
//! callbacks report (a lost device, uncaptured errors).

use super::device_mirror::Resident;
use super::kernel::SCENE_SECTIONS;
use super::rayquery::accel::RayQueryAccels;
use crate::error::{DeviceError, Result, RtError};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// A wgpu device and what the backend keeps on it between launches.
pub struct Gpu {
    /// The adapter, when the runtime opened the device.
    pub(crate) adapter: Option<wgpu::Adapter>,
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) info: wgpu::AdapterInfo,
    pub(crate) limits: wgpu::Limits,
    /// How many of the scene's sections get their own binding (see
    /// [`kernel::SCENE_SECTIONS`]): all of them where the device allows
    /// enough storage buffers per stage.
    pub(crate) scene_bindings: usize,
    /// The one bind-group layout of every megakernel, so bind groups outlive
    /// pipelines.
    pub(crate) layout: wgpu::BindGroupLayout,
    pub(crate) pipelines: HashMap<String, wgpu::ComputePipeline>,
    /// How many pipelines were created (links); for tests of the cache.
    pub pipelines_created: u64,
    /// How many launches encoded the scene (see `SceneKey`), and how many
    /// of those its geometry part too (`GeometryKey`).
    pub scene_encodes: u64,
    /// How many of those encoded the geometry too.
    pub geometry_encodes: u64,
    pub(crate) resident: Resident,
    pub(crate) health: Arc<Health>,
    /// Whether the device has ray queries (`EXPERIMENTAL_RAY_QUERY`,
    /// requested wherever the adapter has it).
    pub(crate) ray_query: bool,
    /// The ray-query traversal's acceleration structures.
    pub(crate) ray_query_accels: RayQueryAccels,
    /// Bind-group layouts of ray-query kernels, by TLAS slot count: the
    /// compute layout's entries, the side table and the TLASes.
    pub(crate) ray_query_layouts: HashMap<u32, wgpu::BindGroupLayout>,
    /// Which device this is, unique in the process: what the stages'
    /// pipelines and histories are kept against. (wgpu's own equality of
    /// devices compares ids that a device of another instance, one opened
    /// after a loss, repeats.)
    pub(crate) serial: u64,
}

/// The wgpu device a context launches on, for an application that draws
/// with it too (`Context::wgpu_device`).
#[derive(Clone, Debug)]
pub struct WgpuDevice {
    /// The adapter, when the context opened the device itself (`None` for
    /// a device from `Context::use_wgpu_device`).
    pub adapter: Option<wgpu::Adapter>,
    /// The device launches run on.
    pub device: wgpu::Device,
    /// Its queue, which launches submit to.
    pub queue: wgpu::Queue,
    /// The adapter's name, backend and kind.
    pub info: wgpu::AdapterInfo,
}

/// What the device's callbacks report.
#[derive(Default)]
pub(crate) struct Health {
    /// Why the device was lost, once it is (its lost callback writes it).
    pub(crate) lost: Mutex<Option<String>>,
    /// Errors outside any error scope (wgpu's default handler would panic
    /// on them); a launch that finds one fails with it.
    pub(crate) uncaptured: Mutex<Vec<String>>,
    /// Queue submissions the runtime made on the device.
    pub(crate) submissions: std::sync::atomic::AtomicU64,
}

impl Health {
    /// Counts one queue submission.
    pub(crate) fn submitted(&self) {
        self.submissions.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }

    pub(crate) fn lost_reason(&self) -> Option<String> {
        self.lost.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// The error for a launch that failed on the device `adapter`:
    /// `DeviceLost` when the device is gone, else `what` with any uncaptured
    /// wgpu errors.
    pub(crate) fn failure(&self, adapter: String, what: String) -> RtError {
        if let Some(reason) = self.lost_reason() {
            return DeviceError::DeviceLost { adapter, reason }.into();
        }
        match self.take_errors() {
            Some(errors) => DeviceError::Gpu(format!("{what}: {errors}")).into(),
            None => DeviceError::Gpu(what).into(),
        }
    }

    /// The uncaptured errors since the last call, joined.
    pub(crate) fn take_errors(&self) -> Option<String> {
        let errors = std::mem::take(&mut *self.uncaptured.lock().unwrap_or_else(|e| e.into_inner()));
        (!errors.is_empty()).then(|| errors.join("; "))
    }
}

impl Gpu {
    /// Opens the first adapter wgpu finds (a GPU, else lavapipe).
    pub fn new() -> Result<Gpu> {
        Gpu::open(&instance(), None)
    }

    /// Opens the first adapter of `instance` (that can present to
    /// `surface`, if given) with the runtime's features and limits.
    pub fn open(instance: &wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Gpu> {
        super::futures::block(Gpu::open_async(instance, surface))
    }

    /// [`Gpu::open`], awaiting the adapter and the device (a browser page
    /// cannot block on them).
    pub async fn open_async(instance: &wgpu::Instance, surface: Option<&wgpu::Surface<'_>>) -> Result<Gpu> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                compatible_surface: surface,
                ..Default::default()
            })
            .await
            .map_err(|e| {
            DeviceError::Gpu(format!(
                "no wgpu adapter ({e}); on a machine without a GPU install Mesa's lavapipe (`apt-get install mesa-vulkan-drivers`)"
            ))
        })?;
        // Heap, log and one binding per scene section, where the adapter
        // has that many.
        // The ray-query traversal binds its side table too.
        let has_ray_query = adapter.features().contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY);
        let storage = (2 + SCENE_SECTIONS.len() as u32 + has_ray_query as u32)
            .min(adapter.limits().max_storage_buffers_per_shader_stage);
        let limits =
            wgpu::Limits { max_storage_buffers_per_shader_stage: storage, ..wgpu::Limits::downlevel_defaults() }
                .using_resolution(adapter.limits());
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
            max_buffer_size: adapter.limits().max_buffer_size,
            ..limits
        };
        // Timestamps, where the adapter has them: the device's own time of
        // a launch ([`super::Timings::kernel`]).
        let mut required_features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        // Ray queries, where the adapter has them (the ray-query traversal,
        // rayquery/): wgpu marks them experimental, and every acceleration
        // structure limit is 0 unless raised to the adapter's.
        let ray_query = has_ray_query;
        let mut experimental_features = wgpu::ExperimentalFeatures::disabled();
        let mut limits = limits;
        if ray_query {
            required_features |= wgpu::Features::EXPERIMENTAL_RAY_QUERY;
            // SAFETY: wgpu's experimental features may have bugs that cause
            // undefined behaviour in the driver; ray queries are what the
            // ray-query traversal needs, tested on every launch of the
            // suite on lavapipe.
            experimental_features = unsafe { wgpu::ExperimentalFeatures::enabled() };
            let a = adapter.limits();
            limits = wgpu::Limits {
                max_blas_primitive_count: a.max_blas_primitive_count,
                max_blas_geometry_count: a.max_blas_geometry_count,
                max_tlas_instance_count: a.max_tlas_instance_count,
                max_acceleration_structures_per_shader_stage: a.max_acceleration_structures_per_shader_stage,
                max_buffers_and_acceleration_structures_per_shader_stage: a
                    .max_buffers_and_acceleration_structures_per_shader_stage,
                ..limits
            };
        }
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("rt-runtime"),
                required_limits: limits.clone(),
                required_features,
                experimental_features,
                ..Default::default()
            })
            .await
            .map_err(|e| DeviceError::Gpu(format!("cannot open a device on {}: {e}", adapter.get_info().name)))?;
        let mut gpu = Gpu::from_parts(device, queue, adapter.get_info(), limits);
        gpu.adapter = Some(adapter);
        Ok(gpu)
    }

    /// Uses a device the application already has.
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo) -> Gpu {
        let limits = device.limits();
        Gpu::from_parts(device, queue, info, limits)
    }

    pub(crate) fn from_parts(
        device: wgpu::Device,
        queue: wgpu::Queue,
        info: wgpu::AdapterInfo,
        limits: wgpu::Limits,
    ) -> Gpu {
        // An explicit layout: a kernel that never reads a binding (no
        // traces: no `rt_scene`) still takes them all. Heap, log: 2 storage
        // buffers; the rest go to the scene's sections.
        let scene_bindings =
            (limits.max_storage_buffers_per_shader_stage.saturating_sub(2) as usize).clamp(1, SCENE_SECTIONS.len());
        let entries = base_entries(scene_bindings);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rt bindings"),
            entries: &entries,
        });
        let health = Arc::new(Health::default());
        let on_lost = Arc::clone(&health);
        device.set_device_lost_callback(move |reason, message| {
            let why = if message.is_empty() { format!("{reason:?}") } else { format!("{reason:?}: {message}") };
            *on_lost.lost.lock().unwrap_or_else(|e| e.into_inner()) = Some(why);
        });
        let on_error = Arc::clone(&health);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            on_error.uncaptured.lock().unwrap_or_else(|e| e.into_inner()).push(e.to_string());
        }));
        let ray_query = device.features().contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY);
        static SERIALS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        Gpu {
            serial: SERIALS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            adapter: None,
            device,
            queue,
            info,
            limits,
            scene_bindings,
            layout,
            pipelines: HashMap::new(),
            pipelines_created: 0,
            scene_encodes: 0,
            geometry_encodes: 0,
            resident: Resident::default(),
            health,
            ray_query,
            ray_query_accels: RayQueryAccels::default(),
            ray_query_layouts: HashMap::new(),
        }
    }

    /// The bind-group layout of kernels with `slots` TLASes (0: the compute
    /// traversal's).
    pub(crate) fn layout_for(&mut self, slots: u32) -> &wgpu::BindGroupLayout {
        if slots == 0 {
            return &self.layout;
        }
        let Gpu { device, ray_query_layouts, scene_bindings, .. } = self;
        ray_query_layouts.entry(slots).or_insert_with(|| {
            let mut entries = base_entries(*scene_bindings);
            entries.push(buffer_entry(
                super::rayquery::wgsl::SIDE_BINDING,
                wgpu::BufferBindingType::Storage { read_only: true },
            ));
            entries.extend((0..slots).map(|s| wgpu::BindGroupLayoutEntry {
                binding: super::rayquery::wgsl::SIDE_BINDING + 1 + s,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::AccelerationStructure { vertex_return: false },
                count: None,
            }));
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("rt bindings (ray queries)"),
                entries: &entries,
            })
        })
    }

    /// Bytes the last launch wrote to the device (scene, heap pages, log
    /// header, launch uniforms).
    pub fn last_upload_bytes(&self) -> u64 {
        self.resident.uploaded
    }

    /// The adapter's name and type, for messages ("llvmpipe (Cpu)").
    pub fn describe(&self) -> String {
        format!("{} ({:?}, {:?})", self.info.name, self.info.device_type, self.info.backend)
    }

    /// Whether the adapter is a software rasteriser (lavapipe).
    pub fn is_cpu(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    }
}

/// The bindings of every kernel: heap, the first scene section, log and
/// launch uniform (0-3), then the other scene sections.
fn base_entries(scene_bindings: usize) -> Vec<wgpu::BindGroupLayoutEntry> {
    let storage = |read_only| wgpu::BufferBindingType::Storage { read_only };
    let mut entries = vec![
        buffer_entry(0, storage(false)),
        buffer_entry(1, storage(true)),
        buffer_entry(2, storage(false)),
        buffer_entry(3, wgpu::BufferBindingType::Uniform),
    ];
    entries.extend((1..scene_bindings).map(|s| buffer_entry(3 + s as u32, storage(true))));
    entries
}

/// A wgpu instance for headless compute, as every device of the runtime is
/// opened.
///
/// On a machine without a window system (no `XDG_RUNTIME_DIR`), Mesa's
/// implicit Vulkan layer `VK_LAYER_MESA_device_select` tries to reach a
/// Wayland compositor while adapters are enumerated, and libwayland prints
/// "error: XDG_RUNTIME_DIR is invalid or not set in the environment." to
/// stderr each time. The layer only reorders devices, which wgpu's own
/// power preference decides anyway, so there the runtime turns it off the
/// way its manifest offers (`NODEVICE_SELECT=1`), once, before it creates
/// its first instance. A user's own setting of either variable wins.
pub fn instance() -> wgpu::Instance {
    // (A browser has no environment to set, nor Mesa.)
    #[cfg(not(target_arch = "wasm32"))]
    static QUIET: std::sync::Once = std::sync::Once::new();
    #[cfg(not(target_arch = "wasm32"))]
    QUIET.call_once(|| {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none() && std::env::var_os("NODEVICE_SELECT").is_none() {
            // SAFETY: runs once, before the runtime has created any Vulkan
            // instance (so before any driver thread of ours reads the
            // environment); std's own environment accesses are locked.
            unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
        }
    });
    wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env())
}

/// The adapter wgpu would pick, without opening a device.
pub fn probe() -> Option<wgpu::AdapterInfo> {
    probe_adapter().map(|a| a.get_info())
}

/// Whether the adapter wgpu would pick has ray queries (the ray-query
/// traversal), without opening a device.
pub fn probe_ray_queries() -> bool {
    probe_adapter().is_some_and(|a| a.features().contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY))
}

/// The adapter wgpu would pick (in a browser, none: the page's adapter
/// comes only asynchronously, and a probe may not block).
fn probe_adapter() -> Option<wgpu::Adapter> {
    let instance = instance();
    super::futures::now(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        ..Default::default()
    }))?
    .ok()
}
