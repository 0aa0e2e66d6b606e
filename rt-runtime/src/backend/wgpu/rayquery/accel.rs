//! Acceleration structures on the device for the ray-query traversal, kept
//! across launches: one BLAS per part of a geometry group (its triangle
//! geometry instances, one BLAS geometry each; its custom primitives'
//! boxes from their bounding-box programs), keyed by the stamp of the
//! group's tree in the acceleration cache, so moving vertices rebuilds only
//! the BLASes over them; one TLAS per traced root, rebuilt when its
//! instances (transforms, masks, BLASes) changed, so moving a transform
//! rebuilds only TLASes. Also the kernel's side table (`rt_query_side`, see
//! search.wgsl).
//!
//! Opacity: a triangle geometry is built `OPAQUE` (its triangles commit in
//! the hardware, no candidate reaches the kernel) when no material of its
//! instance has an any-hit program for any ray type and every material
//! index is in range; a BLAS is rebuilt when that changes (an any-hit
//! program set after a launch). Per ray type, the side table says whether
//! no traced geometry needs a candidate for that type: its traces force the
//! query opaque, so a ray type without any-hit programs takes the fast
//! path on geometry that another type's any-hit programs keep non-opaque.
//!
//! OptiX's builder names: `Sbvh`, `Bvh` and `MedianBvh` ask the driver for
//! fast traces (`PREFER_FAST_TRACE`), `Lbvh` and `NoAccel` for fast builds
//! (`PREFER_FAST_BUILD`); `TriangleKdTree` is refused as everywhere.

use super::flatten::{Flat, FlatInstance, parts};
use crate::accel::Builder;
use crate::accel::cache::{AccelCache, NodeAccel, instance_mesh, prim_bounds};
use crate::error::{DeviceError, Result};
use crate::handles::GeometryInstanceId;
use crate::scene::{NodeId, NodeKind, Scene};
use std::collections::HashMap;
use wgpu::util::DeviceExt;

/// A geometry group's BLASes: `[triangles, boxes]`, each absent when the
/// group has none of that kind.
struct GroupBlas {
    stamp: u64,
    /// Which build this is (TLASes over an older one are rebuilt).
    build: u64,
    parts: [Option<wgpu::Blas>; 2],
    /// Per triangle geometry instance (part 0, in order): whether its
    /// material indices are all in range (fixed while the stamp is), and
    /// whether it was built opaque.
    triangles: Vec<Opacity>,
}

/// What decides whether a triangle geometry instance is opaque.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Opacity {
    gi: u32,
    in_range: bool,
    opaque: bool,
}

/// What a TLAS instance is built from, to tell whether a TLAS changed:
/// `(group, part, the group's BLAS build, transform bits, custom data,
/// mask)`.
type InstanceKey = (u32, u32, u64, [u32; 12], u32, u8);

/// The device's acceleration structures and side table.
#[derive(Default)]
pub(crate) struct RayQueryAccels {
    groups: HashMap<u32, GroupBlas>,
    /// One per root slot.
    tlas: Vec<(Vec<InstanceKey>, wgpu::Tlas)>,
    side: Option<(Vec<u32>, wgpu::Buffer)>,
    /// Per ray type, whether its traces force the query opaque (the side
    /// table's words, for tests).
    pub opaque_ray_types: Vec<bool>,
    /// BLASes built, TLASes built (for tests and the benchmark).
    pub blas_builds: u64,
    pub tlas_builds: u64,
}

impl RayQueryAccels {
    /// The bind-group entries of the side table and the TLASes (after
    /// [`RayQueryAccels::sync`]).
    pub(crate) fn entries(&self) -> Vec<wgpu::BindGroupEntry<'_>> {
        let mut out = Vec::new();
        if let Some((_, side)) = &self.side {
            out.push(wgpu::BindGroupEntry { binding: super::wgsl::SIDE_BINDING, resource: side.as_entire_binding() });
        }
        for (s, (_, tlas)) in self.tlas.iter().enumerate() {
            out.push(wgpu::BindGroupEntry {
                binding: super::wgsl::SIDE_BINDING + 1 + s as u32,
                resource: tlas.as_binding(),
            });
        }
        out
    }
}

/// The driver's build preference for a builder.
fn build_flags(builder: Builder) -> wgpu::AccelerationStructureFlags {
    match builder {
        Builder::Lbvh | Builder::NoAccel => wgpu::AccelerationStructureFlags::PREFER_FAST_BUILD,
        _ => wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
    }
}

/// A 3x4 row-major matrix, as TLAS instances take it.
fn rows(m: glam::Mat4) -> [f32; 12] {
    let r = |i: usize| m.row(i);
    let (a, b, c) = (r(0), r(1), r(2));
    [a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w, c.x, c.y, c.z, c.w]
}

/// Whether geometry instance `gi`'s material indices are all in range (an
/// index past the materials is never hit, as in the compute traversal,
/// which only a candidate can say).
fn materials_in_range(scene: &Scene, gi: u32) -> bool {
    let rec = &scene.instances[gi as usize];
    match instance_mesh(scene, gi).and_then(|mesh| mesh.material_indices.as_ref()) {
        Some(indices) => indices.iter().all(|&m| (m as usize) < rec.materials.len()),
        None => !rec.materials.is_empty(),
    }
}

/// Whether a material of geometry instance `gi` has an any-hit program for
/// ray type `ray_type` (for any ray type: `None`).
fn has_any_hit(scene: &Scene, gi: u32, ray_type: Option<usize>) -> bool {
    scene.instances[gi as usize].materials.iter().any(|m| {
        let any_hit = &scene.materials[m.index() as usize].any_hit;
        match ray_type {
            Some(r) => any_hit.get(r).is_some_and(Option::is_some),
            None => any_hit.iter().any(Option::is_some),
        }
    })
}

/// The opacity of triangle geometry instances `gis`, reusing what `known`
/// says of their material ranges (unchanged while the group's tree is).
fn opacity(scene: &Scene, gis: &[u32], known: Option<&[Opacity]>) -> Vec<Opacity> {
    gis.iter()
        .enumerate()
        .map(|(i, &gi)| {
            let in_range = match known.and_then(|k| k.get(i)).filter(|o| o.gi == gi) {
                Some(o) => o.in_range,
                None => materials_in_range(scene, gi),
            };
            Opacity { gi, in_range, opaque: in_range && !has_any_hit(scene, gi, None) }
        })
        .collect()
}

/// Per ray type, whether no triangle geometry of `groups` needs a candidate
/// for it: no any-hit program of that type, every material index in range.
fn opaque_ray_types(scene: &Scene, groups: &HashMap<u32, GroupBlas>) -> Vec<bool> {
    let triangles: Vec<&Opacity> = groups.values().flat_map(|g| &g.triangles).collect();
    (0..scene.ray_type_count() as usize)
        .map(|r| triangles.iter().all(|o| o.in_range && !has_any_hit(scene, o.gi, Some(r))))
        .collect()
}

fn bytes<T: Copy>(v: &[T]) -> &[u8] {
    // SAFETY: only called with f32 and u32 arrays (no padding, any byte
    // pattern valid as u8).
    unsafe { std::slice::from_raw_parts(v.as_ptr() as *const u8, std::mem::size_of_val(v)) }
}

/// The input buffers and size descriptors of one BLAS, alive until its
/// build is recorded.
enum BlasInput {
    Triangles { sizes: Vec<wgpu::BlasTriangleGeometrySizeDescriptor>, buffers: Vec<(wgpu::Buffer, wgpu::Buffer)> },
    Boxes { sizes: Vec<wgpu::BlasAABBGeometrySizeDescriptor>, buffers: Vec<wgpu::Buffer> },
}

/// Makes the device hold the BLASes of `flat`'s groups, its roots' TLASes
/// and the side table; returns whether a binding changed (the bind groups
/// over them are stale) and whether anything was built (then this waited
/// for the device to finish the builds, so that their time is theirs).
pub(crate) fn sync(
    (device, queue, limits, adapter): (&wgpu::Device, &wgpu::Queue, &wgpu::Limits, &str),
    rq: &mut RayQueryAccels,
    scene: &Scene,
    accels: &AccelCache,
    flat: &Flat,
) -> Result<(bool, bool)> {
    let adapter = adapter.to_string();
    let mut replaced = false;

    let builds = sync_blases((device, limits, &adapter), rq, scene, accels, flat)?;
    let tlas_builds = sync_tlases(device, limits, &adapter, rq, flat)?;
    replaced |= !tlas_builds.is_empty();

    // Record every build in one submission.
    let built = !builds.is_empty() || !tlas_builds.is_empty();
    if built {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rt accels") });
        let entries: Vec<wgpu::BlasBuildEntry> = builds.iter().map(|(blas, input)| build_entry(blas, input)).collect();
        encoder.build_acceleration_structures(entries.iter(), tlas_builds.iter().map(|&s| &rq.tlas[s].1));
        queue.submit([encoder.finish()]);
        let _ = device.poll(wgpu::PollType::wait_indefinitely());
        if let Some(e) = crate::backend::futures::now(scope.pop()).flatten() {
            rq.groups.clear();
            rq.tlas.clear();
            return Err(
                DeviceError::Gpu(format!("building the ray-query acceleration structures on {adapter}: {e}")).into()
            );
        }
    }

    // The side table.
    rq.opaque_ray_types = opaque_ray_types(scene, &rq.groups);
    let words = side_table(scene, flat, &rq.groups, &rq.opaque_ray_types);
    if rq.side.as_ref().is_none_or(|(w, _)| *w != words) {
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("rt_query_side"),
            contents: bytes(&words),
            usage: wgpu::BufferUsages::STORAGE,
        });
        rq.side = Some((words, buffer));
        replaced = true;
    }
    Ok((replaced, built))
}

/// Makes `rq` hold a BLAS for each geometry group `flat` reaches, new
/// ones for the groups whose trees changed (or are new); returns the new
/// BLASes with their inputs, to build.
fn sync_blases(
    (device, limits, adapter): (&wgpu::Device, &wgpu::Limits, &str),
    rq: &mut RayQueryAccels,
    scene: &Scene,
    accels: &AccelCache,
    flat: &Flat,
) -> Result<Vec<(wgpu::Blas, BlasInput)>> {
    let adapter = adapter.to_string();
    // BLASes of the groups whose trees changed (or are new).
    let mut used: Vec<NodeId> = flat.roots.iter().flat_map(|(_, insts)| insts.iter().map(|i| i.group)).collect();
    used.sort();
    used.dedup();
    rq.groups.retain(|g, _| used.iter().any(|u| u.index() == *g));
    let stamp_of = |g: NodeId| match accels.nodes.get(g.index() as usize) {
        Some(Some(NodeAccel::Prims { stamp, .. })) => *stamp,
        _ => 0,
    };
    let mut builds: Vec<(wgpu::Blas, BlasInput)> = Vec::new();
    let mut new_groups: Vec<(u32, GroupBlas)> = Vec::new();
    for &g in &used {
        let stamp = stamp_of(g);
        let [tris, boxes] = parts(scene, g);
        let kept = rq.groups.get(&g.index()).filter(|b| b.stamp == stamp);
        let triangles = opacity(scene, &tris, kept.map(|b| &b.triangles[..]));
        if kept.is_some_and(|b| b.triangles == triangles) {
            continue;
        }
        let NodeKind::GeometryGroup { accel, .. } = &scene.nodes[g.index() as usize].kind else { continue };
        let flags = build_flags(accel.builder);
        let build = rq.blas_builds + builds.len() as u64;
        let mut group = GroupBlas { stamp, build, parts: [None, None], triangles };
        if !tris.is_empty() {
            let (blas, input) = triangle_blas(device, scene, g, &group.triangles, flags, limits, &adapter)?;
            group.parts[0] = Some(blas.clone());
            builds.push((blas, input));
        }
        if !boxes.is_empty() {
            let built = box_blas(device, scene, g, &boxes, flags, limits, &adapter)?;
            if let Some((blas, input)) = built {
                group.parts[1] = Some(blas.clone());
                builds.push((blas, input));
            }
        }
        new_groups.push((g.index(), group));
    }
    rq.blas_builds += builds.len() as u64;
    rq.groups.extend(new_groups);
    Ok(builds)
}

/// Makes `rq` hold a TLAS for each of `flat`'s roots, a new one where an
/// instance changed; returns the slots of the new ones, to build.
fn sync_tlases(
    device: &wgpu::Device,
    limits: &wgpu::Limits,
    adapter: &str,
    rq: &mut RayQueryAccels,
    flat: &Flat,
) -> Result<Vec<usize>> {
    let adapter = adapter.to_string();
    // TLASes: one per root, rebuilt when an instance changed.
    let mut tlas_builds: Vec<usize> = Vec::new();
    rq.tlas.truncate(flat.roots.len());
    for (slot, (root, instances)) in flat.roots.iter().enumerate() {
        let mut keys: Vec<InstanceKey> = Vec::new();
        for FlatInstance { group, record, object_to_world, mask, .. } in instances {
            let Some(blas) = rq.groups.get(&group.index()) else { continue };
            for part in 0..2u32 {
                if blas.parts[part as usize].is_some() {
                    let custom = record * 2 + part;
                    keys.push((
                        group.index(),
                        part,
                        blas.build,
                        rows(*object_to_world).map(f32::to_bits),
                        custom,
                        *mask,
                    ));
                }
            }
        }
        if keys.len() as u64 > limits.max_tlas_instance_count as u64 {
            return Err(DeviceError::AccelerationLimit {
                node: root.index(),
                what: "TLAS instances (paths down to geometry groups)",
                count: keys.len() as u64,
                limit: limits.max_tlas_instance_count as u64,
                adapter: adapter.clone(),
            }
            .into());
        }
        if keys.iter().any(|k| k.4 >= 1 << 24) {
            return Err(DeviceError::AccelerationLimit {
                node: root.index(),
                what: "instance records (the 24 bits of a TLAS instance's custom data hold two per record)",
                count: flat.records as u64,
                limit: 1 << 23,
                adapter: adapter.clone(),
            }
            .into());
        }
        if rq.tlas.get(slot).is_some_and(|(k, _)| *k == keys) {
            continue;
        }
        let mut tlas = device.create_tlas(&wgpu::CreateTlasDescriptor {
            label: Some("rt tlas"),
            max_instances: keys.len().max(1) as u32,
            flags: wgpu::AccelerationStructureFlags::PREFER_FAST_TRACE,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        });
        for (i, k) in keys.iter().enumerate() {
            let blas = rq.groups[&k.0].parts[k.1 as usize].as_ref().expect("a part with a key has a BLAS");
            tlas[i] = Some(wgpu::TlasInstance::new(blas, k.3.map(f32::from_bits), k.4, k.5));
        }
        if slot < rq.tlas.len() {
            rq.tlas[slot] = (keys, tlas);
        } else {
            rq.tlas.push((keys, tlas));
        }
        tlas_builds.push(slot);
    }
    rq.tlas_builds += tlas_builds.len() as u64;
    Ok(tlas_builds)
}

/// The build of one BLAS over its recorded inputs.
fn build_entry<'a>(blas: &'a wgpu::Blas, input: &'a BlasInput) -> wgpu::BlasBuildEntry<'a> {
    let geometry = match input {
        BlasInput::Triangles { sizes, buffers } => wgpu::BlasGeometries::TriangleGeometries(
            sizes
                .iter()
                .zip(buffers)
                .map(|(size, (vertices, indices))| wgpu::BlasTriangleGeometry {
                    size,
                    vertex_buffer: vertices,
                    first_vertex: 0,
                    vertex_stride: 12,
                    index_buffer: Some(indices),
                    first_index: Some(0),
                    transform_buffer: None,
                    transform_buffer_offset: None,
                })
                .collect(),
        ),
        BlasInput::Boxes { sizes, buffers } => wgpu::BlasGeometries::AabbGeometries(
            sizes
                .iter()
                .zip(buffers)
                .map(|(size, boxes)| wgpu::BlasAabbGeometry {
                    size,
                    stride: wgpu::AABB_GEOMETRY_MIN_STRIDE,
                    aabb_buffer: boxes,
                    primitive_offset: 0,
                })
                .collect(),
        ),
    };
    wgpu::BlasBuildEntry { blas, geometry }
}

/// Fails when a BLAS of `group` would pass the adapter's limits (its
/// geometries, and its primitives over all of them).
fn check_blas(group: NodeId, geometries: usize, primitives: u64, limits: &wgpu::Limits, adapter: &str) -> Result<()> {
    let over = |what, count: u64, limit: u32| {
        DeviceError::AccelerationLimit {
            node: group.index(),
            what,
            count,
            limit: limit as u64,
            adapter: adapter.to_string(),
        }
        .into()
    };
    if geometries as u64 > limits.max_blas_geometry_count as u64 {
        return Err(over("BLAS geometries (geometry instances)", geometries as u64, limits.max_blas_geometry_count));
    }
    if primitives > limits.max_blas_primitive_count as u64 {
        return Err(over("BLAS primitives", primitives, limits.max_blas_primitive_count));
    }
    Ok(())
}

/// The BLAS of group `g`'s triangle geometry instances `gis`.
fn triangle_blas(
    device: &wgpu::Device,
    scene: &Scene,
    g: NodeId,
    gis: &[Opacity],
    flags: wgpu::AccelerationStructureFlags,
    limits: &wgpu::Limits,
    adapter: &str,
) -> Result<(wgpu::Blas, BlasInput)> {
    let mut sizes = Vec::new();
    let mut buffers = Vec::new();
    let mut primitives = 0u64;
    for &Opacity { gi, opaque, .. } in gis {
        let Some(mesh) = instance_mesh(scene, gi) else { continue };
        primitives += mesh.indices.len() as u64;
        let geometry_flags = if opaque {
            wgpu::AccelerationStructureGeometryFlags::OPAQUE
        } else {
            wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION
        };
        sizes.push(wgpu::BlasTriangleGeometrySizeDescriptor {
            vertex_format: wgpu::VertexFormat::Float32x3,
            vertex_count: mesh.positions.len() as u32,
            index_format: Some(wgpu::IndexFormat::Uint32),
            index_count: Some(mesh.indices.len() as u32 * 3),
            flags: geometry_flags,
        });
        let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let indices: Vec<u32> = mesh.indices.iter().flatten().copied().collect();
        let input = |label, contents| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::BLAS_INPUT,
            })
        };
        buffers.push((input("rt blas vertices", bytes(&positions)), input("rt blas indices", bytes(&indices))));
    }
    check_blas(g, sizes.len(), primitives, limits, adapter)?;
    let blas = device.create_blas(
        &wgpu::CreateBlasDescriptor {
            label: Some("rt blas triangles"),
            flags,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        },
        wgpu::BlasGeometrySizeDescriptors::Triangles { descriptors: sizes.clone() },
    );
    Ok((blas, BlasInput::Triangles { sizes, buffers }))
}

/// The BLAS of group `g`'s custom-primitive geometry instances `gis`: each
/// primitive's box from its bounding-box program (the acceleration build
/// refused boxes with a NaN, infinite or inverted bound as
/// `SceneError::BadBounds`; an empty box, a primitive that can never be hit,
/// is written as Vulkan's inactive primitive: a NaN minimum). None when no
/// instance has a primitive.
fn box_blas(
    device: &wgpu::Device,
    scene: &Scene,
    g: NodeId,
    gis: &[u32],
    flags: wgpu::AccelerationStructureFlags,
    limits: &wgpu::Limits,
    adapter: &str,
) -> Result<Option<(wgpu::Blas, BlasInput)>> {
    let mut sizes = Vec::new();
    let mut buffers = Vec::new();
    let mut primitives = 0u64;
    for &gi in gis {
        let (_, bounds, _) = prim_bounds(scene, &[GeometryInstanceId(gi)])?;
        primitives += bounds.len() as u64;
        let mut words: Vec<f32> = Vec::with_capacity(bounds.len().max(1) * 6);
        for b in &bounds {
            if b.min.is_finite() && b.max.is_finite() && b.min.cmple(b.max).all() {
                words.extend([b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z]);
            } else {
                words.extend([f32::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]);
            }
        }
        if bounds.is_empty() {
            // No primitives: one inactive box, so that BLAS geometry
            // indices stay the instances' positions in the part.
            words.extend([f32::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]);
        }
        let flags = wgpu::AccelerationStructureGeometryFlags::NO_DUPLICATE_ANY_HIT_INVOCATION;
        sizes.push(wgpu::BlasAABBGeometrySizeDescriptor { primitive_count: (words.len() / 6) as u32, flags });
        buffers.push(device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("rt blas boxes"),
            contents: bytes(&words),
            usage: wgpu::BufferUsages::BLAS_INPUT,
        }));
    }
    if sizes.is_empty() {
        return Ok(None);
    }
    check_blas(g, sizes.len(), primitives, limits, adapter)?;
    let blas = device.create_blas(
        &wgpu::CreateBlasDescriptor {
            label: Some("rt blas boxes"),
            flags,
            update_mode: wgpu::AccelerationStructureUpdateMode::Build,
        },
        wgpu::BlasGeometrySizeDescriptors::AABBs { descriptors: sizes.clone() },
    );
    Ok(Some((blas, BlasInput::Boxes { sizes, buffers })))
}

/// The kernel's side table (search.wgsl): the node and ray type counts,
/// whether each ray type's traces are forced opaque, two words per node
/// (its TLAS slot, where its TLAS instances' paths are), then two words per
/// instance record (where its parts' geometry instances start), then those
/// lists, and each root's paths: two words per TLAS instance, in the
/// TLAS's order (its instance index and id, `instance_index()`).
fn side_table(scene: &Scene, flat: &Flat, groups: &HashMap<u32, GroupBlas>, opaque_ray_types: &[bool]) -> Vec<u32> {
    let n = scene.nodes.len();
    let nodes = 2 + opaque_ray_types.len();
    let base = nodes + 2 * n;
    let mut words = vec![u32::MAX; base + flat.records as usize * 2];
    words[0] = n as u32;
    words[1] = opaque_ray_types.len() as u32;
    for (r, &opaque) in opaque_ray_types.iter().enumerate() {
        words[2 + r] = opaque as u32;
    }
    for (slot, (root, _)) in flat.roots.iter().enumerate() {
        words[nodes + 2 * root.index() as usize] = slot as u32;
    }
    let mut listed = vec![false; flat.records as usize];
    for (_, instances) in &flat.roots {
        for inst in instances {
            if listed[inst.record as usize] || !groups.contains_key(&inst.group.index()) {
                continue;
            }
            listed[inst.record as usize] = true;
            for (part, gis) in parts(scene, inst.group).into_iter().enumerate() {
                if gis.is_empty() {
                    continue;
                }
                words[base + inst.record as usize * 2 + part] = words.len() as u32;
                words.extend(gis);
            }
        }
    }
    // The paths, as `sync` lists the TLAS instances: a part each.
    for (root, instances) in &flat.roots {
        words[nodes + 2 * root.index() as usize + 1] = words.len() as u32;
        for inst in instances {
            let Some(blas) = groups.get(&inst.group.index()) else { continue };
            for part in &blas.parts {
                if part.is_some() {
                    words.extend([inst.path.base, inst.path.id]);
                }
            }
        }
    }
    words
}
