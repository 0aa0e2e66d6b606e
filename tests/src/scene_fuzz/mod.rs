//! A differential fuzzer for the scene graph: random graphs of
//! groups, transforms (rotated, scaled, mirrored, nearly singular),
//! selectors, geometry groups sharing geometry and nodes, visibility masks,
//! custom spheres and triangle meshes, any-hit programs that ignore or
//! terminate, and ray flags, rendered on every backend and compared per
//! launch index.
//!
//! ## Design
//! 1. [`generate`] makes a [`Graph`] from a seed and an index: a DAG of
//!    nodes (children before parents, so a node may be shared by several
//!    parents), its geometry, its instances' materials and variables, the
//!    camera, the ray flags and the ray mask. Graphs come in four shape
//!    [`Class`]es, each with its own kernel on wgpu: triangles only or with
//!    spheres and any-hit programs, two-level (a group of instances) or a
//!    full graph with nested groups, transforms above groups and selectors.
//! 2. Every graph runs the one fixed set of programs in [`programs`], so a
//!    context per class and backend is reused across graphs (each graph
//!    adds its nodes and becomes `top`): the kernel, keyed by the program
//!    set and the whole scene's shape, is relinked only when a stack grows.
//!    A context is replaced every [`GRAPHS_PER_CONTEXT`] graphs of its class,
//!    so the scene (encoded whole on wgpu) stays small.
//! 3. [`check`] compares: hit or miss exactly, the hit's id (instance and
//!    primitive) exactly, `t` and the instance's origin within a relative
//!    bound. Rays that pass within an epsilon of a triangle's edge, graze
//!    its plane, touch a sphere's silhouette, meet two surfaces at the same
//!    distance, or enter a side-choosing selector with a direction on its
//!    plane are skipped (counted): there the backends may legitimately
//!    differ. Where the ray terminates on its first hit (the flag, or an
//!    any hit that terminates and is not disabled), which hit is not
//!    defined between backends: only hit or miss is compared.
//!
//! `RT_SCENE_FUZZ=<graphs>`, `RT_SCENE_FUZZ_SEED=<seed>` and
//! `RT_SCENE_FUZZ_ONLY=<index>` choose what a run does.

pub mod check;
pub mod programs;
mod random;

use crate::fuzz::generate::Rng;
use programs::*;
use rt_runtime::*;
use rt_std::prelude::*;
use std::fmt::Write;

pub use random::generate;

/// Launch size per graph (square).
pub const SIZE: u32 = 20;
/// Graphs of one class that share a context.
pub const GRAPHS_PER_CONTEXT: usize = 40;

/// What a run does.
#[derive(Clone, Debug)]
pub struct Config {
    pub seed: u64,
    pub first: usize,
    pub graphs: usize,
    /// The wgpu side's traversal.
    pub traversal: Traversal,
}

impl Config {
    pub fn from_env(seed: u64, graphs: usize, traversal: Traversal) -> Config {
        let var = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
        let seed = var("RT_SCENE_FUZZ_SEED").unwrap_or(seed);
        let graphs = var("RT_SCENE_FUZZ").map_or(graphs, |n| n as usize);
        match var("RT_SCENE_FUZZ_ONLY") {
            Some(i) => Config { seed, first: i as usize, graphs: 1, traversal },
            None => Config { seed, first: 0, graphs, traversal },
        }
    }
}

/// A graph's kernel shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Class {
    /// Spheres (an intersection program) and any-hit programs.
    pub custom: bool,
    /// Nested groups, transforms above groups, selectors.
    pub deep: bool,
}

impl Class {
    pub const ALL: [Class; 4] = [
        Class { custom: false, deep: false },
        Class { custom: true, deep: false },
        Class { custom: false, deep: true },
        Class { custom: true, deep: true },
    ];
}

#[derive(Clone, Debug)]
pub enum Geom {
    Triangles { positions: Vec<Vec3>, indices: Vec<[u32; 3]> },
    Spheres(Vec<Vec4>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Material {
    Plain,
    Ignore,
    Terminate,
}

#[derive(Clone, Debug)]
pub struct Instance {
    pub geom: usize,
    pub material: Material,
    /// 1-based: ids are `instance_id * 64 + primitive`.
    pub id: u32,
    pub ignore_every: u32,
}

#[derive(Clone, Debug)]
pub enum NodeKind {
    GeometryGroup(Vec<usize>),
    Group(Vec<usize>),
    Transform(Mat4, usize),
    /// Visit rule (see [`programs::fuzz_visit`]) and children.
    Selector(u32, Vec<usize>),
}

#[derive(Clone, Debug)]
pub struct Node {
    pub kind: NodeKind,
    pub mask: u8,
    pub builder: Builder,
}

/// One generated scene and how it is looked at.
#[derive(Clone, Debug)]
pub struct Graph {
    pub class: Class,
    pub geoms: Vec<Geom>,
    pub instances: Vec<Instance>,
    /// Children before parents; the last is the root.
    pub nodes: Vec<Node>,
    pub flags: u32,
    pub ray_mask: u32,
    pub eye: Vec3,
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
}

impl Graph {
    pub fn root(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Whether the hit a ray reports is defined between backends: not when
    /// it may stop at its first hit.
    pub fn which_hit_defined(&self) -> bool {
        let terminate_ah = self.instances.iter().any(|i| i.material == Material::Terminate);
        self.flags & RAY_FLAG_TERMINATE_ON_FIRST_HIT == 0
            && !(terminate_ah && self.flags & RAY_FLAG_DISABLE_ANYHIT == 0)
    }

    /// World-space ray of launch index `(x, y)`, as the camera computes it.
    pub fn ray(&self, x: u32, y: u32) -> (Vec3, Vec3) {
        let p = |i: u32| (i as f32 + 0.5) / SIZE as f32 * 2.0 - 1.0;
        (self.eye, (self.forward + self.right * p(x) + self.up * p(y)).normalize())
    }

    /// A readable description: flags, mask, camera, then the DAG from the root.
    pub fn describe(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "class {:?}, flags {:#x}, ray mask {:#x}, eye {}, forward {}",
            self.class, self.flags, self.ray_mask, self.eye, self.forward
        );
        for (i, g) in self.geoms.iter().enumerate() {
            match g {
                Geom::Triangles { positions, indices } => {
                    let _ = writeln!(s, "geometry {i}: {} triangles {positions:?} {indices:?}", indices.len());
                }
                Geom::Spheres(sp) => {
                    let _ = writeln!(s, "geometry {i}: spheres {sp:?}");
                }
            }
        }
        for (i, inst) in self.instances.iter().enumerate() {
            let _ = writeln!(
                s,
                "instance {i}: geometry {}, {:?} (ignore_every {}), id {}",
                inst.geom, inst.material, inst.ignore_every, inst.id
            );
        }
        let mut seen = vec![false; self.nodes.len()];
        self.describe_node(self.root(), 0, &mut seen, &mut s);
        s
    }

    fn describe_node(&self, n: usize, depth: usize, seen: &mut [bool], s: &mut String) {
        let node = &self.nodes[n];
        let pad = "  ".repeat(depth);
        let mask = if node.mask == 0xff { String::new() } else { format!(" mask {:#04x}", node.mask) };
        let again = if seen[n] { " (shared, above)" } else { "" };
        let (line, children): (String, Vec<usize>) = match &node.kind {
            NodeKind::GeometryGroup(insts) => (format!("geometry group {insts:?} {:?}", node.builder), vec![]),
            NodeKind::Group(c) => (format!("group {:?}", node.builder), c.clone()),
            NodeKind::Transform(m, c) => {
                let (sc, r, t) = m.to_scale_rotation_translation();
                (format!("transform scale {sc} rotation {r} translation {t} det {:.3e}", m.determinant()), vec![*c])
            }
            NodeKind::Selector(rule, c) => (format!("selector rule {rule}"), c.clone()),
        };
        let _ = writeln!(s, "{pad}node {n}: {line}{mask}{again}");
        if seen[n] {
            return;
        }
        seen[n] = true;
        for c in children {
            self.describe_node(c, depth + 1, seen, s);
        }
    }
}

/// A context of one class on one backend, with the fixed programs.
pub struct Runner {
    pub ctx: Context,
    out: BufferId,
    origins: BufferId,
    plain: MaterialId,
    ignore: Option<MaterialId>,
    terminate: Option<MaterialId>,
    sphere: Option<(ProgramId, ProgramId)>,
    visit: Option<ProgramId>,
    pub graphs: usize,
}

/// What one backend saw for a graph: `out` and `origins` per launch index.
pub struct Seen {
    pub out: Vec<Vec4>,
    pub origins: Vec<Vec4>,
    pub exceptions: usize,
}

impl Runner {
    pub fn new(backend: Backend, traversal: Traversal, class: Class) -> Runner {
        let mut ctx = Context::new();
        ctx.set_backend(backend);
        ctx.set_traversal(traversal);
        let rg = ctx.create_program(&fuzz_camera::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let miss = ctx.create_program(&fuzz_miss::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, SIZE, SIZE).unwrap();
        let origins = ctx.create_buffer_2d::<Vec4>(BufferType::Output, SIZE, SIZE).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        ctx.set_var(Scope::Context, "origins", origins).unwrap();
        let ch = ctx.create_program(&fuzz_hit::PROGRAM);
        let material = |ctx: &mut Context, ah: Option<&'static rt_std::program::ProgramDescriptor>| {
            let m = ctx.create_material();
            ctx.set_closest_hit_program(m, 0, ch).unwrap();
            if let Some(ah) = ah {
                let p = ctx.create_program(ah);
                ctx.set_any_hit_program(m, 0, p).unwrap();
            }
            m
        };
        let plain = material(&mut ctx, None);
        let (ignore, terminate, sphere) = if class.custom {
            let i = material(&mut ctx, Some(&fuzz_ignore::PROGRAM));
            let t = material(&mut ctx, Some(&fuzz_terminate::PROGRAM));
            let s = (ctx.create_program(&fuzz_sphere::PROGRAM), ctx.create_program(&fuzz_sphere_bounds::PROGRAM));
            (Some(i), Some(t), Some(s))
        } else {
            (None, None, None)
        };
        let visit = class.deep.then(|| ctx.create_program(&fuzz_visit::PROGRAM));
        Runner { ctx, out, origins, plain, ignore, terminate, sphere, visit, graphs: 0 }
    }

    /// Adds `g`'s nodes to the context, makes its root `top` and launches.
    #[allow(clippy::result_large_err)] // rt_runtime::Result, as the context returns it.
    pub fn run(&mut self, g: &Graph) -> Result<Seen> {
        self.graphs += 1;
        let ctx = &mut self.ctx;
        let mut geoms = Vec::new();
        for geom in &g.geoms {
            geoms.push(match geom {
                Geom::Triangles { positions, indices } => ctx.create_triangles(TriangleMesh {
                    positions: positions.clone(),
                    indices: indices.clone(),
                    ..TriangleMesh::default()
                })?,
                Geom::Spheres(s) => {
                    let (isect, bounds) = self.sphere.expect("spheres in a class without custom primitives");
                    let id = ctx.create_custom_geometry(s.len() as u32, isect, bounds)?;
                    let b = ctx.create_buffer(BufferType::Input, s.clone());
                    ctx.set_var(id, "spheres", b)?;
                    id
                }
            });
        }
        let mut insts = Vec::new();
        for inst in &g.instances {
            let m = match inst.material {
                Material::Plain => self.plain,
                Material::Ignore => self.ignore.unwrap(),
                Material::Terminate => self.terminate.unwrap(),
            };
            let gi = ctx.create_geometry_instance(geoms[inst.geom], &[m])?;
            ctx.set_var(gi, "instance_id", inst.id)?;
            if inst.material == Material::Ignore {
                ctx.set_var(gi, "ignore_every", inst.ignore_every)?;
            }
            insts.push(gi);
        }
        let mut ids: Vec<NodeId> = Vec::new();
        for n in &g.nodes {
            let accel = Acceleration::new(n.builder);
            let id = match &n.kind {
                NodeKind::GeometryGroup(c) => {
                    ctx.create_geometry_group(&c.iter().map(|&i| insts[i]).collect::<Vec<_>>(), accel)?
                }
                NodeKind::Group(c) => ctx.create_group(&c.iter().map(|&i| ids[i]).collect::<Vec<_>>(), accel)?,
                NodeKind::Transform(m, c) => ctx.create_transform(*m, ids[*c])?,
                NodeKind::Selector(rule, c) => {
                    let s = ctx.create_selector(self.visit.unwrap(), &c.iter().map(|&i| ids[i]).collect::<Vec<_>>())?;
                    ctx.set_var(s, "visit_rule", *rule)?;
                    ctx.set_var(s, "visit_children", c.len() as u32)?;
                    s
                }
            };
            if n.mask != 0xff {
                ctx.set_visibility_mask(id, n.mask)?;
            }
            ids.push(id);
        }
        ctx.set_var(Scope::Context, "top", ids[g.root()])?;
        ctx.set_var(Scope::Context, "eye", g.eye)?;
        ctx.set_var(Scope::Context, "forward", g.forward)?;
        ctx.set_var(Scope::Context, "right", g.right)?;
        ctx.set_var(Scope::Context, "up", g.up)?;
        ctx.set_var(Scope::Context, "flags", g.flags)?;
        ctx.set_var(Scope::Context, "mask", g.ray_mask)?;
        let report = ctx.launch(0, SIZE, SIZE)?;
        Ok(Seen {
            out: ctx.read_buffer::<Vec4>(self.out)?,
            origins: ctx.read_buffer::<Vec4>(self.origins)?,
            exceptions: report.exceptions.len(),
        })
    }
}

/// A graph whose backends disagree.
pub struct Failure {
    pub index: usize,
    pub description: String,
    pub detail: String,
}

#[derive(Default, Debug)]
pub struct Stats {
    pub graphs: usize,
    pub rays_compared: usize,
    pub rays_hit_only: usize,
    pub skipped: usize,
    pub hits: usize,
    pub mismatched_rays: usize,
    pub pipelines: u64,
    pub contexts: usize,
    /// Graphs whose wgpu launch took the ray-query traversal.
    pub ray_query_graphs: usize,
}

pub struct Report {
    pub stats: Stats,
    pub failures: Vec<Failure>,
}

impl Report {
    pub fn summary(&self) -> String {
        let s = &self.stats;
        format!(
            "scene fuzz: {} graphs, {} rays compared ({} by hit or miss only, {} hits), {} skipped as ambiguous, {} mismatched rays in {} graphs; {} wgpu pipelines created over {} contexts; {} graphs traced with ray queries",
            s.graphs,
            s.rays_compared,
            s.rays_hit_only,
            s.hits,
            s.skipped,
            s.mismatched_rays,
            self.failures.len(),
            s.pipelines,
            s.contexts,
            s.ray_query_graphs
        )
    }
}

/// Runs `cfg`'s graphs on the CPU and wgpu backends and compares them.
pub fn run(cfg: &Config) -> Report {
    let mut stats = Stats::default();
    let mut failures = Vec::new();
    let mut runners: Vec<Option<(Runner, Runner)>> = (0..4).map(|_| None).collect();
    let mut retired_pipelines = 0;
    for index in cfg.first..cfg.first + cfg.graphs {
        let g = generate(cfg.seed, index);
        let slot = Class::ALL.iter().position(|c| *c == g.class).unwrap();
        if runners[slot].as_ref().is_some_and(|(c, _)| c.graphs >= GRAPHS_PER_CONTEXT) {
            let (_, w) = runners[slot].take().unwrap();
            retired_pipelines += w.ctx.pipelines_created();
        }
        let (cpu, gpu) = runners[slot].get_or_insert_with(|| {
            stats.contexts += 1;
            (Runner::new(Backend::Cpu, Traversal::Auto, g.class), Runner::new(Backend::Wgpu, cfg.traversal, g.class))
        });
        stats.graphs += 1;
        let started = std::time::Instant::now();
        let seen = (cpu.run(&g), gpu.run(&g));
        stats.ray_query_graphs += (gpu.ctx.traversal().map(|t| t.0) == Some(Traversal::RayQuery)) as usize;
        if started.elapsed().as_secs_f32() > 2.0 {
            eprintln!("scene fuzz: graph {index} took {:.1?}", started.elapsed());
        }
        let (a, b) = match seen {
            (Ok(a), Ok(b)) => (a, b),
            (a, b) => {
                failures.push(Failure {
                    index,
                    description: g.describe(),
                    detail: format!(
                        "a launch fails: cpu {:?}, wgpu {:?}",
                        a.err().map(|e| e.to_string()),
                        b.err().map(|e| e.to_string())
                    ),
                });
                // The contexts may be unusable for the next graphs.
                runners[slot] = None;
                continue;
            }
        };
        let c = check::compare(&g, &a, &b);
        stats.rays_compared += c.compared;
        stats.rays_hit_only += c.hit_only;
        stats.skipped += c.skipped;
        stats.hits += c.hits;
        stats.mismatched_rays += c.mismatches.len();
        if !c.mismatches.is_empty() || a.exceptions + b.exceptions > 0 {
            let mut detail = format!("exceptions: cpu {}, wgpu {}\n", a.exceptions, b.exceptions);
            for m in c.mismatches.iter().take(12) {
                let _ = writeln!(detail, "{m}");
            }
            if c.mismatches.len() > 12 {
                let _ = writeln!(detail, "... {} more", c.mismatches.len() - 12);
            }
            failures.push(Failure { index, description: g.describe(), detail });
        }
    }
    stats.pipelines = retired_pipelines + runners.iter().flatten().map(|(_, w)| w.ctx.pipelines_created()).sum::<u64>();
    Report { stats, failures }
}

/// The launch index of a flat output index.
pub fn launch_index(i: usize) -> UVec2 {
    UVec2::new(i as u32 % SIZE, i as u32 / SIZE)
}
