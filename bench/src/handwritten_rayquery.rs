//! The hand-written baseline for `megakernel_rayquery_vs_handwritten`: the
//! same primary + AO kernel as [`crate::handwritten`] (its common part),
//! with `closest` a hardware ray query over one opaque BLAS of the mesh
//! (handwritten_rayquery.wgsl) instead of a walk of our own tree. Needs an
//! adapter with `wgpu::Features::EXPERIMENTAL_RAY_QUERY`.

use crate::handwritten::{Measured, adapter, time_runs};
use glam::Vec3;
use rt_runtime::TriangleMesh;
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

fn bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: only f32 and u32 arrays (no padding, any bytes valid as u8).
    unsafe { std::slice::from_raw_parts(v.as_ptr() as *const u8, std::mem::size_of_val(v)) }
}

/// The kernel's source.
pub fn wgsl() -> String {
    format!(
        "enable wgpu_ray_query;\n{}\n{}",
        include_str!("handwritten_common.wgsl"),
        include_str!("handwritten_rayquery.wgsl")
    )
}

/// Runs the AO workload `reps` times; also the acceleration structures'
/// build time (BLAS and TLAS, until the device finished them).
pub fn run(
    mesh: &TriangleMesh,
    cam: (Vec3, Vec3, Vec3, Vec3),
    width: u32,
    height: u32,
    reps: usize,
) -> Result<(Measured, Duration), String> {
    let adapter = adapter()?;
    if !adapter.features().contains(wgpu::Features::EXPERIMENTAL_RAY_QUERY) {
        return Err(format!("{} has no ray queries", adapter.get_info().name));
    }
    let (device, queue) = open_device(&adapter)?;
    let (structures, build) = build_structures(&device, &queue, mesh)?;
    let kernel = Kernel::new(&device, &structures.tlas, mesh, cam, (width, height));
    let measured =
        time_runs(&device, &queue, &kernel.pipeline, &kernel.bind, &kernel.out_b, (width, height), reps, &adapter)?;
    Ok((measured, build))
}

/// A device with ray queries (and timestamps where the adapter has them)
/// and the adapter's limits on bindings and acceleration structures.
fn open_device(adapter: &wgpu::Adapter) -> Result<(wgpu::Device, wgpu::Queue), String> {
    let a = adapter.limits();
    pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: wgpu::Limits {
            max_storage_buffer_binding_size: a.max_storage_buffer_binding_size,
            max_blas_primitive_count: a.max_blas_primitive_count,
            max_blas_geometry_count: a.max_blas_geometry_count,
            max_tlas_instance_count: a.max_tlas_instance_count,
            max_acceleration_structures_per_shader_stage: a.max_acceleration_structures_per_shader_stage,
            ..wgpu::Limits::downlevel_defaults()
        },
        required_features: wgpu::Features::EXPERIMENTAL_RAY_QUERY
            | (adapter.features() & wgpu::Features::TIMESTAMP_QUERY),
        // SAFETY: as the runtime opens its devices (wgpu marks ray queries
        // experimental).
        experimental_features: unsafe { wgpu::ExperimentalFeatures::enabled() },
        ..Default::default()
    }))
    .map_err(|e| e.to_string())
}

/// The mesh's acceleration structures, with the buffers they were built
/// from (kept for the run).
struct Structures {
    _blas: wgpu::Blas,
    tlas: wgpu::Tlas,
    _inputs: [wgpu::Buffer; 2],
}

/// One opaque BLAS of the mesh under a TLAS of one instance, built on the
/// device: the structures and the build's time (until the device finished).
fn build_structures(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    mesh: &TriangleMesh,
) -> Result<(Structures, Duration), String> {
    let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let indices: Vec<u32> = mesh.indices.iter().flatten().copied().collect();
    let input = |contents: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents,
            usage: wgpu::BufferUsages::BLAS_INPUT,
        })
    };
    let (vertices, index_buffer) = (input(bytes(&positions)), input(bytes(&indices)));
    let size = wgpu::BlasTriangleGeometrySizeDescriptor {
        vertex_format: wgpu::VertexFormat::Float32x3,
        vertex_count: mesh.positions.len() as u32,
        index_format: Some(wgpu::IndexFormat::Uint32),
        index_count: Some(indices.len() as u32),
        flags: wgpu::AccelerationStructureGeometryFlags::OPAQUE,
    };
    let built = Instant::now();
    let blas = device.create_blas(
        &wgpu::CreateBlasDescriptor {
            label: None,
            flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        },
        wgpu::BlasGeometrySizeDescriptors::Triangles { descriptors: vec![size.clone()] },
    );
    let mut tlas = device.create_tlas(&wgpu::CreateTlasDescriptor {
        label: None,
        max_instances: 1,
        flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
        update_mode: wgpu::AccelerationStructureUpdateMode::Build,
    });
    tlas[0] =
        Some(wgpu::TlasInstance::new(&blas, [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0], 0, 0xff));
    let mut enc = device.create_command_encoder(&Default::default());
    let geometry = wgpu::BlasTriangleGeometry {
        size: &size,
        vertex_buffer: &vertices,
        first_vertex: 0,
        vertex_stride: 12,
        index_buffer: Some(&index_buffer),
        first_index: Some(0),
        transform_buffer: None,
        transform_buffer_offset: None,
    };
    let entry =
        wgpu::BlasBuildEntry { blas: &blas, geometry: wgpu::BlasGeometries::TriangleGeometries(vec![geometry]) };
    enc.build_acceleration_structures([&entry], [&tlas]);
    queue.submit([enc.finish()]);
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
    let build = built.elapsed();
    Ok((Structures { _blas: blas, tlas, _inputs: [vertices, index_buffer] }, build))
}

/// The kernel's pipeline bound to the TLAS, the triangles, the output and
/// the camera.
struct Kernel {
    pipeline: wgpu::ComputePipeline,
    bind: wgpu::BindGroup,
    out_b: wgpu::Buffer,
    _inputs: [wgpu::Buffer; 2],
}

impl Kernel {
    fn new(
        device: &wgpu::Device,
        tlas: &wgpu::Tlas,
        mesh: &TriangleMesh,
        cam: (Vec3, Vec3, Vec3, Vec3),
        (width, height): (u32, u32),
    ) -> Kernel {
        let (eye, u, v, w) = cam;
        let mut camera: Vec<u32> = Vec::new();
        for c in [eye, u, v, w] {
            camera.extend([c.x, c.y, c.z, 0.0].map(f32::to_bits));
        }
        camera.extend([width, height, 0, 0]);
        let tris: Vec<f32> =
            mesh.indices.iter().flat_map(|t| t.iter().flat_map(|&i| mesh.positions[i as usize].to_array())).collect();
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("handwritten ray query"),
            source: wgpu::ShaderSource::Wgsl(wgsl().into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("handwritten ray query"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let storage = |contents: &[u8], extra| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents,
                usage: wgpu::BufferUsages::STORAGE | extra,
            })
        };
        let pixels = (width * height) as usize;
        let tris_b = storage(bytes(&tris), wgpu::BufferUsages::empty());
        let out_b = storage(bytes(&vec![0u32; pixels * 2]), wgpu::BufferUsages::COPY_SRC);
        let cam_b = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes(&camera),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: tlas.as_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: tris_b.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: out_b.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: cam_b.as_entire_binding() },
            ],
        });
        Kernel { pipeline, bind, out_b, _inputs: [tris_b, cam_b] }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_kernel_is_valid_wgsl() {
        let module = naga::front::wgsl::parse_str(&super::wgsl()).expect("parses");
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::RAY_QUERY)
            .validate(&module)
            .expect("validates");
    }
}
