//! What only the wgpu backend has: its device, the statistics of its
//! launches (encodes, pipelines, bytes moved, the linked megakernel) and
//! the choice of its traversal. Everything a second GPU backend would need
//! to answer is here, in one place; the CPU backend answers none of it
//! (its statistics read zero).

use super::Context;
use crate::backend::Backend;
use crate::backend::wgpu::{Gpu, WgpuBackend};
use crate::error::Result;

impl Context {
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

    /// Testing recovery: the next wgpu launch destroys its device once its
    /// work is submitted, as a driver reset or a removed GPU would. That
    /// launch fails with [`crate::DeviceError::DeviceLost`] and writes no outputs; the
    /// one after opens a new device.
    pub fn simulate_device_loss_in_next_launch(&mut self) {
        self.wgpu_backend().lose_device_in_next_launch();
    }

    /// How many wgpu launches encoded and uploaded the scene (tables, BVH
    /// nodes, triangles); the others found it on the device, unchanged
    /// since, and encoded only the variables and buffers.
    pub fn scene_encodes(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.stats().scene_encodes)
    }

    /// How many of those encodes also encoded the geometry (geometry groups'
    /// BVH nodes, primitive tables and triangles; meshes): the others kept
    /// it on the device and encoded only the rest (transforms, groups,
    /// programs, records) around it.
    pub fn geometry_encodes(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.stats().geometry_encodes)
    }

    /// How many wgpu pipelines (megakernel links) this context created.
    pub fn pipelines_created(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.stats().pipelines_created)
    }

    /// Bytes the last wgpu launch wrote to the device: the pages of the
    /// scene and of the heap (records, buffers, textures) that changed since
    /// the launch before, the log's counters and the launch uniform (0 before
    /// any wgpu launch).
    pub fn last_upload_bytes(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.stats().last_upload_bytes)
    }

    /// Bytes the last wgpu launch read back from its device: the output
    /// buffers (not the device-local ones, [`Context::set_buffer_device_local`]),
    /// the log's header and what it counted, and the timestamps.
    pub fn last_read_back_bytes(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.stats().last_read_back_bytes)
    }

    /// Queue submissions the runtime made on its wgpu device since the
    /// device opened (0 before): one a launch's tile (its dispatches, and
    /// the read-back of its outputs and log), one more where a launch
    /// logged exceptions or prints, one a build of the ray-query
    /// traversal's structures, one or two where device-local words move
    /// or are put aside, one a read of a buffer the device holds, and one
    /// a run of stages ([`Context::run_stage`]) unless it rode in a
    /// command list's launch ([`crate::command_list`]).
    pub fn wgpu_submissions(&self) -> u64 {
        self.wgpu_backend_ref().map_or(0, |b| b.submissions())
    }

    /// The megakernel WGSL of the last wgpu launch (`RT_DUMP_WGSL=1` also
    /// writes it to the temporary directory).
    pub fn linked_wgsl(&self) -> Option<&str> {
        self.wgpu_backend_ref().and_then(|b| b.stats().linked_wgsl)
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
        self.wgpu_backend().set_traversal(traversal);
    }

    /// The traversal [`Context::set_traversal`] asked for.
    pub fn traversal_setting(&self) -> crate::Traversal {
        self.wgpu_backend_ref().map_or(crate::Traversal::Auto, |b| b.traversal_setting())
    }

    /// The traversal the last wgpu launch used (`Compute` or `RayQuery`)
    /// and why; None before any wgpu launch.
    pub fn traversal(&self) -> Option<(crate::Traversal, &str)> {
        self.wgpu_backend_ref().and_then(|b| b.stats().traversal)
    }

    /// How many BLASes (one per kind of geometry in a geometry group) and
    /// TLASes (one per traced root) the ray-query traversal built: a moved
    /// transform rebuilds TLASes only, moved vertices the BLASes over them.
    pub fn ray_query_builds(&self) -> (u64, u64) {
        self.wgpu_backend_ref().map(WgpuBackend::stats).map_or((0, 0), |s| (s.blas_builds, s.tlas_builds))
    }

    /// Per ray type, whether the last launch's ray-query traces of that type
    /// took the opaque path (the query forced opaque: no traced geometry
    /// has an any-hit program for the type, every material index is in
    /// range, so triangles commit without reaching the kernel); `None`
    /// unless the last launch used the ray-query traversal.
    pub fn ray_query_opaque_ray_types(&self) -> Option<Vec<bool>> {
        self.wgpu_backend_ref().and_then(|b| b.stats().opaque_ray_types.map(<[bool]>::to_vec))
    }
}
