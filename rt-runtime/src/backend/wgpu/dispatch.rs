//! Dispatch: a launch as tiles of 8 x 8 workgroups within the device's
//! dispatch limit, each with its launch uniform, and the compute pass over
//! them (with timestamps where the device has them). Ray-query kernels
//! also bind the side table and their TLASes.

use super::Launch;
use super::device::Gpu;
use super::device_mirror::words_to_bytes;
use super::readback::LOG_EXCEPTIONS;
use glam::UVec2;
use rt_abi::records::LaunchUniform;

/// A tile: its launch uniform and its workgroups in x and y.
pub(crate) type Tile = ([u32; LaunchUniform::WORDS], u32, u32);

/// The dispatches of launch `l`'s tile (`l.tile`, whose origin is on the
/// 8 x 8 grid): a tile over the dispatch limit runs as several, each with
/// its uniform (`[case, record]` of the ray-generation and exception
/// programs; the heap word of the bindless buffer table).
pub(crate) fn tiles(
    l: &Launch,
    limits: &wgpu::Limits,
    ray_generation: [u32; 2],
    exception: [u32; 2],
    buffer_table: u32,
) -> Vec<Tile> {
    let (width, height) = (l.width, l.height);
    let (base, size) = (l.tile.origin, l.tile.size);
    let print_filter = l.settings.print_launch_index.unwrap_or(UVec2::splat(u32::MAX));
    let print_enabled = l.settings.print_enabled as u32;
    let tiles_x = size.x.div_ceil(8);
    let tiles_y = size.y.div_ceil(8);
    let max_groups = limits.max_compute_workgroups_per_dimension.max(1);
    let mut tiles: Vec<Tile> = Vec::new();
    let mut y0 = 0;
    while y0 < tiles_y {
        let gy = (tiles_y - y0).min(max_groups);
        let mut x0 = 0;
        while x0 < tiles_x {
            let gx = (tiles_x - x0).min(max_groups);
            let uniform = LaunchUniform {
                dim: [width, height],
                origin: [base.x + x0 * 8, base.y + y0 * 8],
                ray_generation,
                exception,
                log_capacity: LOG_EXCEPTIONS,
                print_enabled,
                print_filter: print_filter.to_array(),
                exceptions: l.settings.exceptions,
                buffer_table,
                depth: l.depth,
                reserved: 0,
            }
            .words();
            tiles.push((uniform, gx, gy));
            x0 += gx;
        }
        y0 += gy;
    }
    tiles
}

/// Writes the tiles' uniforms, makes a bind group per tile (again when a
/// buffer was `replaced`) and records the compute pass of `wgsl`'s
/// pipeline over them; returns the encoder, for the read-back's copies.
pub(crate) fn record(
    gpu: &mut Gpu,
    wgsl: &str,
    slots: u32,
    tiles: &[Tile],
    mut replaced: bool,
) -> wgpu::CommandEncoder {
    let layout = gpu.layout_for(slots).clone();
    let Gpu { device, queue, limits, pipelines, resident: res, ray_query_accels, .. } = gpu;
    let pipeline = &pipelines[wgsl];
    let uniform_bytes = (LaunchUniform::WORDS * 4) as u32;
    let stride = limits.min_uniform_buffer_offset_alignment.max(uniform_bytes) as u64;
    if res.uniforms.as_ref().is_none_or(|(_, slots)| (*slots as usize) < tiles.len()) {
        let slots = tiles.len() as u32;
        res.uniforms = Some((
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("rt_launch"),
                size: stride * slots as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            slots,
        ));
        replaced = true;
    }
    let (uniforms, _) = res.uniforms.as_ref().expect("created above");
    for (i, (uniform, _, _)) in tiles.iter().enumerate() {
        queue.write_buffer(uniforms, i as u64 * stride, words_to_bytes(uniform));
        res.uploaded += uniform_bytes as u64;
    }
    if res.bind_slots != slots {
        res.bind_slots = slots;
        replaced = true;
    }
    if replaced {
        res.bind_groups.clear();
    }
    let heap_buffer = &res.heap.as_ref().expect("synced above").buffer;
    let log = res.log.as_ref().expect("created by the upload");
    let scene_buffers: Vec<&wgpu::Buffer> =
        res.scene.iter().map(|m| &m.as_ref().expect("synced above").buffer).collect();
    while res.bind_groups.len() < tiles.len() {
        let slot = res.bind_groups.len() as u64;
        let mut entries = vec![
            wgpu::BindGroupEntry { binding: 0, resource: heap_buffer.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: scene_buffers[0].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: log.as_entire_binding() },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: uniforms,
                    offset: slot * stride,
                    size: std::num::NonZeroU64::new(uniform_bytes as u64),
                }),
            },
        ];
        for (s, b) in scene_buffers.iter().enumerate().skip(1) {
            entries.push(wgpu::BindGroupEntry { binding: 3 + s as u32, resource: b.as_entire_binding() });
        }
        if slots > 0 {
            entries.extend(ray_query_accels.entries());
        }
        res.bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rt bindings"),
            layout: &layout,
            entries: &entries,
        }));
    }
    if res.timestamps.is_none() && device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        let set = device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("rt launch time"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolved = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("rt launch time"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        res.timestamps = Some((set, resolved));
    }
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt launch") });
    {
        let timestamp_writes = res.timestamps.as_ref().map(|(set, _)| wgpu::ComputePassTimestampWrites {
            query_set: set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("rt launch"), timestamp_writes });
        pass.set_pipeline(pipeline);
        for ((_, gx, gy), bind) in tiles.iter().zip(&res.bind_groups) {
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(*gx, *gy, 1);
        }
    }
    encoder
}
