//! The hand-written baseline for `megakernel_vs_handwritten`: a minimal WGSL
//! kernel (traversal + triangle test + one AO ray, no programs, no
//! dispatch) over the same tree and the same rays, on the same adapter: the
//! CWBVH the megakernel walks for this workload (handwritten_cwbvh.wgsl),
//! and, for comparison, the BVH2 it is converted from (handwritten.wgsl).

use glam::Vec3;
use rt_runtime::TriangleMesh;
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

fn bytes(w: &[u32]) -> &[u8] {
    // SAFETY: u32 has no padding; any bytes are valid u8.
    unsafe { std::slice::from_raw_parts(w.as_ptr() as *const u8, std::mem::size_of_val(w)) }
}

/// The adapter the runtime opens (`PowerPreference::HighPerformance`: a
/// discrete GPU over an integrated one or lavapipe), so both kernels run on
/// the same one.
pub fn adapter() -> Result<wgpu::Adapter, String> {
    let instance = rt_runtime::backend::wgpu::instance();
    let options =
        wgpu::RequestAdapterOptions { power_preference: wgpu::PowerPreference::HighPerformance, ..Default::default() };
    pollster::block_on(instance.request_adapter(&options)).map_err(|e| e.to_string())
}

/// What the kernel measured.
pub struct Measured {
    /// Rays traced by one run.
    pub rays: u64,
    /// Median time of a run: dispatch, wait and read-back.
    pub time: Duration,
    /// Median device time of the dispatch (timestamp queries), where the
    /// adapter has them.
    pub kernel: Option<Duration>,
    /// Process CPU time of the `reps` runs.
    pub cpu: Duration,
    /// The adapter it ran on, as the runtime describes its own.
    pub device: String,
}

/// The tree a hand-written kernel walks.
#[derive(Clone, Copy, PartialEq)]
pub enum Tree {
    /// The BVH2 (handwritten.wgsl), what the megakernel walks with any-hit
    /// or intersection programs.
    Bvh2,
    /// obvhs's CWBVH converted from that BVH2 as the runtime converts it
    /// (handwritten_cwbvh.wgsl), what the megakernel walks otherwise.
    Cwbvh,
}

impl Tree {
    /// The kernel: the common part, then the tree's traversal.
    pub fn wgsl(self) -> String {
        let traversal = match self {
            Tree::Bvh2 => include_str!("handwritten.wgsl"),
            Tree::Cwbvh => include_str!("handwritten_cwbvh.wgsl"),
        };
        format!("{}\n{traversal}", include_str!("handwritten_common.wgsl"))
    }
}

/// A device on `adapter` with its largest storage binding and, where it
/// has them, timestamps (as the runtime opens one).
fn open_device(adapter: &wgpu::Adapter) -> Result<(wgpu::Device, wgpu::Queue), String> {
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: wgpu::Limits {
            max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
            ..wgpu::Limits::downlevel_defaults()
        },
        // As the runtime does: the device's own time of the dispatch.
        required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
        ..Default::default()
    }))
    .map_err(|e| e.to_string())
}

/// The kernel's buffers for `mesh` over `tree`: the BVH2's bounds and
/// links, the triangles (in the CWBVH's primitive order for `Tree::Cwbvh`)
/// and the CWBVH's nodes (empty for `Tree::Bvh2`).
fn encode(mesh: &TriangleMesh, tree: Tree) -> (Vec<u32>, Vec<u32>, Vec<u32>, Vec<u32>) {
    // The BVH the runtime builds: obvhs medium_build, one primitive a leaf.
    let prim_bounds: Vec<obvhs::aabb::Aabb> = mesh
        .indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            obvhs::aabb::Aabb::new(a.min(b).min(c).into(), a.max(b).max(c).into())
        })
        .collect();
    let mut core = Duration::ZERO;
    let params = obvhs::BvhBuildParams { max_prims_per_leaf: 1, ..obvhs::BvhBuildParams::medium_build() };
    let bvh = obvhs::bvh2::builder::build_bvh2(&prim_bounds, params, &mut core);
    let mut bounds: Vec<u32> = Vec::with_capacity(bvh.nodes.len() * 6);
    let mut links: Vec<u32> = Vec::with_capacity(bvh.nodes.len() * 3);
    for n in &bvh.nodes {
        let b = n.aabb();
        let prim = if n.prim_count > 0 { bvh.primitive_indices[n.first_index as usize] } else { 0 };
        bounds.extend([b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z].map(f32::to_bits));
        links.extend([n.prim_count, n.first_index, prim]);
    }
    // Triangles by index, or in the CWBVH's primitive order.
    let cwbvh = (tree == Tree::Cwbvh).then(|| obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh(&bvh, 3, true, false));
    let order: Vec<u32> = match &cwbvh {
        Some(cw) => cw.primitive_indices.clone(),
        None => (0..mesh.indices.len() as u32).collect(),
    };
    let mut tris: Vec<u32> = Vec::with_capacity(mesh.indices.len() * 9);
    for t in &order {
        for i in mesh.indices[*t as usize] {
            let p = mesh.positions[i as usize];
            tris.extend([p.x, p.y, p.z].map(f32::to_bits));
        }
    }
    let cw_nodes: Vec<u32> =
        cwbvh.iter().flat_map(|cw| cw.nodes.iter().flat_map(rt_runtime::backend::wgpu::cwbvh_node_words)).collect();
    (bounds, links, tris, cw_nodes)
}

/// Runs the AO workload `reps` times over `tree`, or says why it could not
/// run.
pub fn run(
    mesh: &TriangleMesh,
    cam: (Vec3, Vec3, Vec3, Vec3),
    width: u32,
    height: u32,
    reps: usize,
    tree: Tree,
) -> Result<Measured, String> {
    let adapter = adapter()?;
    let max_binding = adapter.limits().max_storage_buffer_binding_size;
    // BVH2 nodes (2n - 1 for n triangles) of 24 bytes of bounds and 12 of
    // links, each array in its own binding, and 36 bytes a triangle.
    let biggest = (mesh.indices.len() as u64 * 2 * 24).max(mesh.indices.len() as u64 * 36);
    if biggest > max_binding {
        return Err(format!(
            "the BVH needs a {} MiB storage buffer but the adapter binds at most {} MiB",
            biggest >> 20,
            max_binding >> 20
        ));
    }
    let (device, queue) = open_device(&adapter)?;
    let (bounds, links, tris, cw_nodes) = encode(mesh, tree);
    let (eye, u, v, w) = cam;
    let mut camera: Vec<u32> = Vec::new();
    for c in [eye, u, v, w] {
        camera.extend([c.x, c.y, c.z, 0.0].map(f32::to_bits));
    }
    camera.extend([width, height, 0, 0]);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("handwritten"),
        source: wgpu::ShaderSource::Wgsl(tree.wgsl().into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("handwritten"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let storage = |w: &[u32], extra| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes(w),
            usage: wgpu::BufferUsages::STORAGE | extra,
        })
    };
    let bounds_b = storage(&bounds, wgpu::BufferUsages::empty());
    let links_b = storage(&links, wgpu::BufferUsages::empty());
    let tris_b = storage(&tris, wgpu::BufferUsages::empty());
    let pixels = (width * height) as usize;
    let out_b = storage(&vec![0u32; pixels * 2], wgpu::BufferUsages::COPY_SRC);
    let cam_b = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytes(&camera),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let cw_b = storage(&cw_nodes, wgpu::BufferUsages::empty());
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: if tree == Tree::Cwbvh { cw_b.as_entire_binding() } else { bounds_b.as_entire_binding() },
        },
        wgpu::BindGroupEntry { binding: 1, resource: tris_b.as_entire_binding() },
        wgpu::BindGroupEntry { binding: 2, resource: out_b.as_entire_binding() },
        wgpu::BindGroupEntry { binding: 3, resource: cam_b.as_entire_binding() },
    ];
    if tree == Tree::Bvh2 {
        entries.push(wgpu::BindGroupEntry { binding: 4, resource: links_b.as_entire_binding() });
    }
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    time_runs(&device, &queue, &pipeline, &bind, &out_b, (width, height), reps, &adapter)
}

/// Runs `pipeline` over `bind` at `width` x `height`, `reps` times after one
/// warm-up run, and counts the rays it traced from `out_b`: one value a
/// pixel, then a 1.0 for every pixel whose primary ray hit (whose AO ray
/// was traced).
#[allow(clippy::too_many_arguments)]
pub(crate) fn time_runs(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    pipeline: &wgpu::ComputePipeline,
    bind: &wgpu::BindGroup,
    out_b: &wgpu::Buffer,
    (width, height): (u32, u32),
    reps: usize,
    adapter: &wgpu::Adapter,
) -> Result<Measured, String> {
    let pixels = (width * height) as usize;
    let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY).then(|| {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: None,
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        (set, resolved)
    });
    let mut times = Vec::new();
    let mut kernel_times = Vec::new();
    let mut rays = 0u64;
    let mut cpu = Duration::ZERO;
    for _ in 0..reps + 1 {
        let t = Instant::now();
        let c = crate::peers::process_cpu_time();
        let read = device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: (pixels * 8 + 16) as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let timestamp_writes = timestamps.as_ref().map(|(set, _)| wgpu::ComputePassTimestampWrites {
                query_set: set,
                beginning_of_pass_write_index: Some(0),
                end_of_pass_write_index: Some(1),
            });
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor { label: None, timestamp_writes });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
        }
        enc.copy_buffer_to_buffer(out_b, 0, &read, 0, (pixels * 8) as u64);
        if let Some((set, resolved)) = &timestamps {
            enc.resolve_query_set(set, 0..2, resolved, 0);
            enc.copy_buffer_to_buffer(resolved, 0, &read, (pixels * 8) as u64, 16);
        }
        queue.submit([enc.finish()]);
        let slice = read.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
        let data = slice.get_mapped_range().map_err(|e| e.to_string())?;
        if timestamps.is_some() {
            let t =
                |i: usize| u64::from_le_bytes(data[pixels * 8 + i..pixels * 8 + i + 8].try_into().expect("8 bytes"));
            let ns = t(8).saturating_sub(t(0)) as f64 * queue.get_timestamp_period() as f64;
            kernel_times.push(Duration::from_nanos(ns as u64));
        }
        let hits = data[pixels * 4..pixels * 8]
            .chunks_exact(4)
            .filter(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) == 1.0)
            .count();
        rays = (pixels + hits) as u64;
        drop(data);
        read.unmap();
        times.push(t.elapsed());
        if times.len() > 1 {
            cpu += crate::peers::process_cpu_time().saturating_sub(c);
        }
    }
    // The first run includes the pipeline's compilation on some drivers.
    times.remove(0);
    let kernel = (!kernel_times.is_empty()).then(|| crate::peers::median(kernel_times.split_off(1)));
    let info = adapter.get_info();
    let device = format!("{} ({:?}, {:?})", info.name, info.device_type, info.backend);
    Ok(Measured { rays, time: crate::peers::median(times), kernel, cpu, device })
}

#[cfg(test)]
mod tests {
    use crate::{peers, scenes};

    #[test]
    fn the_kernels_are_valid_wgsl() {
        for tree in [super::Tree::Bvh2, super::Tree::Cwbvh] {
            let module = naga::front::wgsl::parse_str(&tree.wgsl()).expect("parses");
            naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
                .validate(&module)
                .expect("validates");
        }
    }

    /// Equal work: the kernel traces as many rays as obvhs's traversal of
    /// the same triangles (one AO ray per primary hit), up to the odd grazing
    /// ray that the two triangle tests round differently.
    #[test]
    fn the_kernel_traces_the_rays_obvhs_traces() {
        let dir = scenes::scenes_dir().expect("the shared scenes");
        let teapot = scenes::BenchScene {
            name: "teapot",
            mesh: scenes::load_obj(&dir.join("teapot.obj")).expect("teapot.obj"),
            view: glam::Vec3::new(0.0, 0.1, 2.2),
            source: String::new(),
        };
        let (w, h) = (96, 72);
        let cam = teapot.camera(w, h);
        let tris = teapot.obvhs_triangles();
        let (bvh, _) = peers::obvhs_cwbvh(&tris);
        let obvhs = peers::obvhs_ao(&bvh, &tris, cam, w, h);
        let primary_hits = obvhs.primary_t.iter().filter(|t| t.is_finite()).count() as u64;
        assert!(primary_hits > 500, "the teapot is in view: {primary_hits} hits");
        for tree in [super::Tree::Bvh2, super::Tree::Cwbvh] {
            let rays = super::run(&teapot.mesh, cam, w, h, 1, tree).expect("runs on the wgpu adapter").rays;
            assert!(obvhs.rays.abs_diff(rays) <= 3, "hand-written kernel {rays} rays, obvhs {}", obvhs.rays);
        }
    }
}
