//! The generator: [`generate`] makes graph `index` of a seed's sequence,
//! node by node (children before parents), then its ray flags, ray mask
//! and camera.

use super::*;

fn f(rng: &mut Rng, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * (rng.below(1 << 24) as f32 / (1u32 << 24) as f32)
}

fn unit(rng: &mut Rng) -> Vec3 {
    loop {
        let v = Vec3::new(f(rng, -1.0, 1.0), f(rng, -1.0, 1.0), f(rng, -1.0, 1.0));
        if v.length_squared() > 0.05 && v.length_squared() <= 1.0 {
            return v.normalize();
        }
    }
}

fn chance(rng: &mut Rng, p: f32) -> bool {
    f(rng, 0.0, 1.0) < p
}

fn random_geom(rng: &mut Rng, custom: bool) -> Geom {
    let kinds = if custom { 3 } else { 2 };
    match rng.below(kinds) {
        0 => {
            // A quad (two triangles sharing a diagonal), its corners jittered.
            let h = f(rng, 0.4, 1.2);
            let mut positions =
                vec![Vec3::new(-h, -h, 0.0), Vec3::new(h, -h, 0.0), Vec3::new(h, h, 0.0), Vec3::new(-h, h, 0.0)];
            for p in &mut positions {
                *p += Vec3::new(f(rng, -0.2, 0.2), f(rng, -0.2, 0.2), f(rng, -0.1, 0.1));
            }
            Geom::Triangles { positions, indices: vec![[0, 1, 2], [0, 2, 3]] }
        }
        1 => {
            // A tetrahedron: a closed mesh.
            let r = f(rng, 0.4, 1.0);
            let mut positions = vec![
                Vec3::new(1.0, 1.0, 1.0),
                Vec3::new(1.0, -1.0, -1.0),
                Vec3::new(-1.0, 1.0, -1.0),
                Vec3::new(-1.0, -1.0, 1.0),
            ];
            for p in &mut positions {
                *p = *p * r + Vec3::new(f(rng, -0.15, 0.15), f(rng, -0.15, 0.15), f(rng, -0.15, 0.15));
            }
            Geom::Triangles { positions, indices: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]] }
        }
        _ => {
            let n = 1 + rng.below(3) as usize;
            Geom::Spheres(
                (0..n)
                    .map(|_| {
                        Vec3::new(f(rng, -0.8, 0.8), f(rng, -0.8, 0.8), f(rng, -0.8, 0.8)).extend(f(rng, 0.2, 0.6))
                    })
                    .collect(),
            )
        }
    }
}

fn random_transform(rng: &mut Rng) -> Mat4 {
    let rotation = Mat4::from_axis_angle(unit(rng), f(rng, -3.0, 3.0));
    let translation = Vec3::new(f(rng, -1.2, 1.2), f(rng, -1.2, 1.2), f(rng, -1.2, 1.2));
    let mut scale = match rng.below(3) {
        0 => Vec3::splat(f(rng, 0.6, 1.4)),
        _ => Vec3::new(f(rng, 0.6, 1.4), f(rng, 0.6, 1.4), f(rng, 0.6, 1.4)),
    };
    match rng.below(8) {
        // Mirrored: a negative determinant.
        0 | 1 => scale[rng.below(3) as usize] *= -1.0,
        // Nearly singular but invertible.
        2 => scale[rng.below(3) as usize] = 1e-3,
        3 => scale[rng.below(3) as usize] = 2e-2,
        _ => {}
    }
    // Sometimes a shear too (not a scale-rotation-translation).
    let shear = if chance(rng, 0.2) {
        let mut m = Mat4::IDENTITY;
        m.x_axis.y = f(rng, -0.5, 0.5);
        m
    } else {
        Mat4::IDENTITY
    };
    Mat4::from_translation(translation) * rotation * Mat4::from_scale(scale) * shear
}

fn random_mask(rng: &mut Rng) -> u8 {
    if chance(rng, 0.8) { 0xff } else { [0x00, 0x01, 0x02, 0x03, 0xfe][rng.below(5) as usize] }
}

/// A builder any node may use (spatial splits need triangles: geometry
/// groups of meshes get `Sbvh` at times, see [`generate`]).
fn random_builder(rng: &mut Rng) -> Builder {
    [Builder::Bvh, Builder::MedianBvh, Builder::Lbvh, Builder::NoAccel][rng.below(4) as usize]
}

/// Graph `index` of `seed`'s sequence.
pub fn generate(seed: u64, index: usize) -> Graph {
    let mut rng = Rng::new(seed ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let class = Class::ALL[index % 4];
    let geoms: Vec<Geom> = (0..1 + rng.below(3)).map(|_| random_geom(&mut rng, class.custom)).collect();
    let instances = random_instances(&mut rng, class, geoms.len());
    let mut g = Graph {
        class,
        geoms,
        instances,
        nodes: Vec::new(),
        flags: 0,
        ray_mask: 0xff,
        eye: Vec3::ZERO,
        forward: Vec3::ZERO,
        right: Vec3::ZERO,
        up: Vec3::ZERO,
    };
    // Node heights, for sharing a node only where it fits the depth bound.
    let mut heights: Vec<u32> = Vec::new();
    let max_depth = if class.deep { 2 + rng.below(3) as u32 } else { 2 };
    root(&mut g, &mut heights, &mut rng, max_depth);
    aim(&mut g, &mut rng);
    g
}

/// Two to five instances of the `geoms` geometries, with materials that
/// ignore or terminate where the class has any-hit programs.
fn random_instances(rng: &mut Rng, class: Class, geoms: usize) -> Vec<Instance> {
    (0..2 + rng.below(4) as usize)
        .map(|i| Instance {
            geom: rng.below(geoms as u64) as usize,
            material: if !class.custom {
                Material::Plain
            } else {
                [Material::Plain, Material::Plain, Material::Ignore, Material::Terminate][rng.below(4) as usize]
            },
            id: i as u32 + 1,
            ignore_every: 1 + rng.below(4) as u32,
        })
        .collect()
}

/// The root, the graph's last node: now and then a geometry group alone
/// (two-level graphs), else a group of one to four nodes below
/// `max_depth`.
fn root(g: &mut Graph, heights: &mut Vec<u32>, rng: &mut Rng, max_depth: u32) {
    let deep = g.class.deep;
    if !deep && chance(rng, 0.1) {
        geometry_group(g, heights, rng);
    } else {
        let n = 1 + rng.below(4) as usize;
        let children: Vec<usize> = (0..n).map(|_| node(g, heights, rng, max_depth - 1, deep)).collect();
        let ht = 1 + children.iter().map(|&c| heights[c]).max().unwrap();
        push(g, heights, rng, NodeKind::Group(children), ht);
    }
}

/// The ray flags, the ray mask and the camera: outside the scene on a
/// random direction, looking at the origin.
fn aim(g: &mut Graph, rng: &mut Rng) {
    g.flags = [
        RAY_FLAG_NONE,
        RAY_FLAG_NONE,
        RAY_FLAG_DISABLE_ANYHIT,
        RAY_FLAG_TERMINATE_ON_FIRST_HIT,
        RAY_FLAG_CULL_BACK_FACING,
        RAY_FLAG_CULL_FRONT_FACING,
        RAY_FLAG_DISABLE_CLOSESTHIT,
        RAY_FLAG_CULL_BACK_FACING | RAY_FLAG_DISABLE_ANYHIT,
    ][rng.below(8) as usize];
    g.ray_mask = [0xff, 0xff, 0xff, 0x01, 0x02, 0x03][rng.below(6) as usize];
    let dir = unit(rng);
    g.eye = dir * f(rng, 6.0, 9.0);
    g.forward = -dir;
    let helper = if dir.y.abs() < 0.9 { Vec3::Y } else { Vec3::X };
    let spread = f(rng, 0.12, 0.25);
    g.right = dir.cross(helper).normalize() * -spread;
    g.up = g.right.cross(g.forward).normalize() * spread;
}

/// Appends a node of height `h` (its mask and builder drawn) and gives
/// its index.
fn push(g: &mut Graph, heights: &mut Vec<u32>, rng: &mut Rng, kind: NodeKind, h: u32) -> usize {
    let mask = random_mask(rng);
    let builder = random_builder(rng);
    g.nodes.push(Node { kind, mask, builder });
    heights.push(h);
    g.nodes.len() - 1
}

/// A geometry group of one to three instances of distinct geometries
/// (built with `Sbvh` now and then where they are all meshes).
fn geometry_group(g: &mut Graph, heights: &mut Vec<u32>, rng: &mut Rng) -> usize {
    let n = 1 + rng.below(3) as usize;
    let insts = (0..n).map(|_| rng.below(g.instances.len() as u64) as usize).collect::<Vec<_>>();
    // Instances of distinct geometries: two instances of one geometry
    // in one group would meet every ray at the same distance.
    let mut insts = insts.clone();
    insts.sort_unstable_by_key(|i| g.instances[*i].geom);
    insts.dedup_by_key(|i| g.instances[*i].geom);
    let meshes = insts.iter().all(|&i| matches!(g.geoms[g.instances[i].geom], Geom::Triangles { .. }));
    let n = push(g, heights, rng, NodeKind::GeometryGroup(insts), 0);
    if meshes && chance(rng, 0.25) {
        g.nodes[n].builder = Builder::Sbvh;
    }
    n
}

/// A node of height at most `h` (0: a geometry group).
fn node(g: &mut Graph, heights: &mut Vec<u32>, rng: &mut Rng, h: u32, deep: bool) -> usize {
    // Share an existing node now and then (instancing of subgraphs).
    if !heights.is_empty() && chance(rng, 0.3) {
        let fits: Vec<usize> = (0..heights.len()).filter(|&i| heights[i] <= h).collect();
        if !fits.is_empty() {
            let pick = fits[rng.below(fits.len() as u64) as usize];
            // Shared children get a transform of their own, so that
            // their copies are not at the same place.
            if h >= 1 && heights[pick] < h {
                let m = random_transform(rng);
                return push(g, heights, rng, NodeKind::Transform(m, pick), heights[pick] + 1);
            }
        }
    }
    if h == 0 || chance(rng, 0.2) {
        return geometry_group(g, heights, rng);
    }
    if !deep {
        // Two-level: transforms (chains) over geometry groups.
        let child =
            if h >= 2 && chance(rng, 0.3) { node(g, heights, rng, 1, deep) } else { geometry_group(g, heights, rng) };
        let m = random_transform(rng);
        return push(g, heights, rng, NodeKind::Transform(m, child), heights[child] + 1);
    }
    match rng.below(5) {
        0 | 1 => {
            let child = node(g, heights, rng, h - 1, deep);
            let m = random_transform(rng);
            push(g, heights, rng, NodeKind::Transform(m, child), heights[child] + 1)
        }
        2 | 3 => {
            let n = 1 + rng.below(4) as usize;
            let children: Vec<usize> = (0..n).map(|_| node(g, heights, rng, h - 1, deep)).collect();
            let ht = 1 + children.iter().map(|&c| heights[c]).max().unwrap();
            push(g, heights, rng, NodeKind::Group(children), ht)
        }
        _ => {
            let n = 2 + rng.below(2) as usize;
            let children: Vec<usize> = (0..n).map(|_| node(g, heights, rng, h - 1, deep)).collect();
            let ht = 1 + children.iter().map(|&c| heights[c]).max().unwrap();
            let rule = rng.below(2) as u32;
            push(g, heights, rng, NodeKind::Selector(rule, children), ht)
        }
    }
}
