//! The megakernel linker: one WGSL compute shader per (entry point, program
//! set, graph shape), assembled from the runtime prelude, every program's
//! types, helpers and body (deduplicated by name), dispatch `switch`es and
//! per-depth clones of everything that traces.
//!
//! WGSL has no recursion, so `rt_trace_<P>` is cloned per depth:
//! `rt_trace_<P>_d<k>` runs the closest-hit and miss programs' depth-`k`
//! clones, whose own traces call depth `k + 1`; past the context's maximum
//! depth the trace raises `EXCEPTION_TRACE_DEPTH_EXCEEDED` instead.
//!
//! Visit programs (selectors) run through `rt_visit_dispatch(case, vars)`,
//! which passes the traced payload by value and returns the chosen child;
//! a visit program taking another payload type than the traced ray's raises
//! `EXCEPTION_INVALID_RAY` and chooses nothing, as on the CPU backend.
//!
//! Variable values are never in the text: each program use reads them from
//! its scope record in the heap (offset passed at dispatch), so changing a
//! value never relinks.

mod callables;
mod clones;
mod stack;
mod switch_arms;

use crate::error::{LinkError, Result};
use crate::link::{self, callables::LinkedCallable};
use clones::{Linked, at_depth, clone_estimate, helpers_that_trace, per_depth_clones};
use rt_std::program::{ProgramDescriptor, ProgramKind, TriangleBuiltin, TypeLayout, VariableKind};
use std::collections::{BTreeMap, BTreeSet};
use switch_arms::Arms;

/// The runtime's half of every module, after the contract's records, heap
/// and exception codes (see [`prelude`]).
const PRELUDE: &str = include_str!("../prelude.wgsl");
const HITS: &str = include_str!("hits.wgsl");
const TRAVERSE: &str = include_str!("../compute/traverse.wgsl");
const GRAPH: &str = include_str!("../compute/graph.wgsl");
const MOTION: &str = include_str!("../compute/motion.wgsl");

/// The start of every module: the records and heap binding the programs
/// were validated against (rt-abi's, not a copy; of atomic words when
/// `atomic`: some linked program updates buffer elements atomically), the
/// exception codes and ray flags, the launch uniform, the instance record's
/// and node table's constants, then the runtime's implementations of the
/// contract's functions.
pub fn prelude(atomic: bool) -> String {
    let mut out = String::from(rt_abi::wgsl::RECORDS);
    out.push_str(rt_abi::wgsl::heap(atomic));
    out.push_str(&rt_abi::wgsl::floats());
    out.push_str(&rt_abi::wgsl::constants());
    out.push_str(&rt_abi::records::LaunchUniform::wgsl());
    out.push_str(&rt_abi::records::InstanceRecord::wgsl_constants());
    out.push_str(&rt_abi::records::NodeEntry::wgsl_constants());
    out.push_str(&rt_abi::records::BufferTable::wgsl_constants());
    out.push_str(&rt_abi::records::SamplerTable::wgsl_constants());
    out.push_str(&rt_abi::wgsl::exception_kind_bits());
    out.push_str(PRELUDE);
    out
}

/// What a kernel without graph traversal links in its place: hits take
/// their transforms from the instance table.
const TWO_LEVEL: &str = "
fn rt_commit_xform() {}
fn rt_hit_xform() {
    let ib = rt_scene[1] + rt_h_inst * RT_INST_WORDS;
    rt_o2w = rt_m4(ib);
    rt_w2o = rt_m4(ib + RT_INST_W2O);
}
fn rt_search_graph(object: u32, mask: u32) {}
";

/// What kernels whose hits carry their own transforms link (the graph
/// traversal: instances under transform entries; ray queries: the committed
/// intersection's matrices): the committed hit's transforms, kept.
const KEPT_XFORM: &str = "
var<private> rt_h_o2w: mat4x4<f32>;
var<private> rt_h_w2o: mat4x4<f32>;
fn rt_commit_xform() {
    rt_h_o2w = rt_o2w;
    rt_h_w2o = rt_w2o;
}
fn rt_hit_xform() {
    rt_o2w = rt_h_o2w;
    rt_w2o = rt_h_w2o;
}
";

/// A program the kernel may dispatch to, with its case id (> 0).
#[derive(Clone, Copy)]
pub struct KernelProgram {
    /// Its case in the kernel's dispatch switch.
    pub case: u32,
    /// The program, as `#[rt_program]` described it.
    pub desc: &'static ProgramDescriptor,
}

/// What the kernel is linked for.
pub struct KernelSpec {
    /// The entry point's ray-generation program.
    pub ray_generation: KernelProgram,
    /// Its exception program (`None`: the default one).
    pub exception: Option<KernelProgram>,
    /// Every closest-hit, any-hit, miss, intersection and visit program in
    /// use.
    pub programs: Vec<KernelProgram>,
    /// The context's maximum trace depth.
    pub max_depth: u32,
    /// 0 when every node is an instance or a group of instances (the
    /// two-level fast path alone); otherwise the graph traversal is linked
    /// with this many transform levels (1 + the deepest nesting of
    /// transforms above groups or selectors).
    pub graph_levels: u32,
    /// Entries of the BVH traversal stack (at least the deepest BVH's
    /// levels + 1: nothing is ever dropped).
    pub bvh_stack: u32,
    /// Entries of the search stack over a group's BVH (`rt_search`: BVH
    /// nodes and the instances of a leaf, so at least the deepest group
    /// BVH's levels + the largest leaf); 0 when the scene has no group of
    /// instances, and `rt_search` no loop over one.
    pub tlas_stack: u32,
    /// Entries of the graph traversal stack.
    pub graph_stack: u32,
    /// Without an exception program: the word offset, in the ray-generation
    /// record, of the `RwBuffer2d<Vec4>` the default exception program
    /// paints.
    pub default_exception: Option<u32>,
    /// How many of the scene's sections ([`SCENE_SECTIONS`]) have their
    /// own storage binding (at least 1: the tables); the others live in the
    /// tables' binding after the tables.
    pub scene_bindings: usize,
    /// No intersection and no any-hit program: every primitive is a
    /// triangle and every candidate commits, so instances are searched by
    /// the lean loop (`rt_blas_triangles` in traverse.wgsl).
    pub triangles_only: bool,
    /// Entries of the lean loop's CWBVH stack (at least the deepest
    /// CWBVH's levels + 1) where every geometry group has a CWBVH over
    /// triangles (`rt_blas_cwbvh`); 0 where the lean loop walks BVH2s.
    pub cwbvh_stack: u32,
    /// TLASes the ray-query traversal binds (0: the compute traversal is
    /// linked instead; see `rayquery/`).
    pub ray_query_slots: u32,
    /// The context's callable programs.
    pub callables: Vec<LinkedCallable>,
}

/// The scene's sections, each its own read-only storage binding where the
/// device allows enough storage buffers per stage (binding 1 for the
/// first, `3 + s` for section `s > 0`), so a scene binds when each section
/// fits the adapter's binding limit rather than the whole. The tables are
/// read as `rt_scene[w]`; every other section through its accessor
/// `fn <accessor>(w: u32) -> u32`: a plain load from its binding, or, for a
/// section that shares the tables' binding, a load at the base the tables'
/// header word `SCENE_HEADER_BASES + s` holds.
pub const SCENE_SECTIONS: [SceneSection; 3] = [
    SceneSection { binding: "rt_scene", accessor: "", what: "the scene's tables (instances, geometry, records)" },
    SceneSection { binding: "rt_bvh", accessor: "rt_node_word", what: "the scene's BVH nodes" },
    SceneSection { binding: "rt_tris", accessor: "rt_tri_word", what: "the scene's triangles in BVH order" },
];

/// Header word of the tables holding section `s`'s base in the merged
/// binding (`SCENE_HEADER_BASES + s`).
pub const SCENE_HEADER_BASES: usize = 8;

/// One part of the scene data: its WGSL binding name, accessor, and what it
/// holds (for errors).
pub struct SceneSection {
    /// The WGSL name of its binding.
    pub binding: &'static str,
    /// The WGSL function that reads a word of it.
    pub accessor: &'static str,
    /// What it holds, in words, for errors.
    pub what: &'static str,
}

/// The WGSL declarations of the scene's sections past the tables (which
/// the prelude declares as `rt_scene`) and their accessors.
pub fn scene_access(bindings: usize) -> String {
    let mut out = String::from("\n// ---- scene sections (see kernel.rs `SCENE_SECTIONS`) ----\n");
    for (s, sec) in SCENE_SECTIONS.iter().enumerate().skip(1) {
        let load = if s < bindings {
            out.push_str(&format!("@group(0) @binding({}) var<storage, read> {}: array<u32>;\n", 3 + s, sec.binding));
            format!("{}[w]", sec.binding)
        } else {
            format!("rt_scene[rt_scene[{}u] + w]", SCENE_HEADER_BASES + s)
        };
        out.push_str(&format!("fn {}(w: u32) -> u32 {{ return {load}; }}\n", sec.accessor));
    }
    out
}

/// Size in heap words of a variable's value in a scope record.
pub fn variable_words(kind: &VariableKind, ty: &TypeLayout) -> u32 {
    match kind {
        VariableKind::Value => ty.words,
        VariableKind::Buffer { .. } | VariableKind::Sampler | VariableKind::SamplerCube => 4,
        VariableKind::Sampler3d => 5,
        VariableKind::Object => 1,
    }
}

fn mangle(layout: &TypeLayout) -> &'static str {
    // Payload and attribute types are user structs: their WGSL name is the
    // mangled name the compiler uses for them.
    layout.wgsl
}

/// The variable arguments of a call: loads from the record at `vars`.
fn var_args(desc: &ProgramDescriptor, vars: &str) -> Vec<String> {
    let mut offset = 0;
    desc.variables
        .iter()
        .map(|v| {
            let a = format!("{}({vars} + {offset}u)", v.wgsl_load);
            offset += variable_words(&v.kind, &v.ty);
            a
        })
        .collect()
}

fn traces(desc: &ProgramDescriptor) -> bool {
    !desc.traced_payloads.is_empty()
}

/// The most copies of the traversal that per-depth clones may inline before
/// a kernel runs its programs from one loop instead.
pub const MAX_CLONES: u64 = 16;

/// The generated megakernel.
pub struct Generated {
    /// The megakernel's WGSL source.
    pub wgsl: String,
    /// What the caller should tell the user when it creates the pipeline
    /// (once per pipeline, not per launch).
    pub warning: Option<String>,
}

/// Generates the megakernel's WGSL.
pub fn generate(spec: &KernelSpec) -> Result<Generated> {
    let mut all: Vec<KernelProgram> = vec![spec.ray_generation];
    all.extend(spec.exception);
    all.extend(spec.programs.iter().copied());

    // The callables some linked program calls, and their signatures.
    let (called, callables) = link::callables::linked(all.iter().map(|p| p.desc), &spec.callables)?;
    // Types and shared functions, deduplicated by name.
    let with_callables: Vec<KernelProgram> =
        all.iter().copied().chain(callables.iter().map(|c| KernelProgram { case: c.id, desc: c.desc })).collect();
    let (types, functions) = linked_items(&with_callables)?;
    let tracing_helpers = helpers_that_trace(&functions);

    let (payloads, attributes) = payloads_and_attributes(&all);

    // One program's atomic update makes the whole heap atomic words: the
    // binding has one type, and the same buffer may be another program's.
    let atomic = rt_abi::wgsl::needs_atomic_heap(functions.keys().copied());
    let mut out = runtime_part(spec, atomic);
    out.push_str("\n// ---- types ----\n");
    for (item, _) in types.values() {
        out.push_str(item.text);
    }
    // Every tracing program resumable and per-depth clones would be many:
    // one loop runs them all. Few clones (nothing traces from a closest hit
    // or miss, or shallow recursion) inline into a smaller, faster kernel.
    let clones = clone_estimate(spec, &all, &functions, &tracing_helpers);
    let stuck = all.iter().find(|p| traces(p.desc) && p.desc.wgsl_resumable.is_none());
    let resumable = stuck.is_none() && clones > MAX_CLONES;
    // Pipeline creation grows with the copies: minutes on Mesa at a few
    // hundred, out of memory beyond.
    let warning = stuck.filter(|_| clones > MAX_CLONES).map(|p| {
        format!(
            "rt-runtime: warning: the megakernel inlines about {clones} copies of the traversal (maximum trace depth {}) because `{}` ({}) has no resumable form ({}); creating its pipeline may take long. Lower the depth with `set_max_trace_depth`, or move that trace into a statement of its own.",
            spec.max_depth,
            p.desc.name,
            p.desc.location(),
            p.desc.not_resumable.unwrap_or("unknown reason"),
        )
    });
    out.push_str("\n// ---- shared functions ----\n");
    for (name, (item, _)) in &functions {
        if tracing_helpers.contains(*name) && resumable {
            // Only their resumable forms are called.
        } else if tracing_helpers.contains(*name) {
            for d in 0..=spec.max_depth {
                out.push_str(&at_depth(item.text, item.sites, d, &tracing_helpers));
            }
        } else {
            out.push_str(item.text);
        }
    }

    out.push_str(&payload_and_attribute_state(&payloads, &attributes));

    let payload_ids: BTreeMap<&str, u32> = payloads.keys().enumerate().map(|(i, w)| (*w, i as u32)).collect();
    if !called.is_empty() {
        out.push_str("\n// ---- callables ----\n");
        out.push_str(&callables::callable_functions(&called, &callables, &functions));
        out.push_str(&callables::dispatch(&called, &callables));
    }
    out.push_str("\n// ---- dispatch ----\n");
    out.push_str(&dispatch_intersection(&spec.programs));
    out.push_str(&dispatch_any_hit(&spec.programs));
    if spec.graph_levels > 0 {
        out.push_str(&dispatch_visit(&spec.programs, &payload_ids));
    }
    let run_ray_generation = if !all.iter().any(|p| traces(p.desc)) {
        // Nothing traces: no trace loop, no traversal in the kernel.
        let mut emitted: BTreeSet<&str> = BTreeSet::new();
        out.push_str("\n// ---- programs ----\n");
        for p in &all {
            if emitted.insert(p.desc.wgsl_entry) {
                out.push_str(p.desc.wgsl_program);
            }
        }
        let rg = spec.ray_generation.desc;
        format!("{}({});", rg.wgsl_entry, var_args(rg, "rt_launch.ray_generation.y").join(", "))
    } else if resumable {
        out.push_str(&stack::stack_machine(spec, &all, &payload_ids));
        "rt_run();".to_string()
    } else {
        out.push_str(&per_depth_clones(spec, &all, &payloads, &payload_ids, &tracing_helpers));
        format!(
            "{}_d0({});",
            spec.ray_generation.desc.wgsl_entry,
            var_args(spec.ray_generation.desc, "rt_launch.ray_generation.y").join(", ")
        )
    };

    out.push_str(&entry_point(spec, &run_ray_generation));
    Ok(Generated { wgsl: out, warning })
}

/// The payload types `all` take or trace, and the attribute types they
/// take, by WGSL name.
fn payloads_and_attributes(
    all: &[KernelProgram],
) -> (BTreeMap<&'static str, TypeLayout>, BTreeMap<&'static str, TypeLayout>) {
    let mut payloads: BTreeMap<&str, TypeLayout> = BTreeMap::new();
    let mut attributes: BTreeMap<&str, TypeLayout> = BTreeMap::new();
    for p in all {
        if let Some(pl) = p.desc.payload {
            payloads.insert(pl.wgsl, pl);
        }
        for pl in p.desc.traced_payloads {
            payloads.insert(pl.wgsl, *pl);
        }
        if let Some(a) = p.desc.attributes {
            attributes.insert(a.wgsl, a);
        }
    }
    (payloads, attributes)
}

/// The runtime's part of the kernel, before the programs' types: the
/// ray-query extension where the kernel uses it, the prelude (over a heap
/// of atomic words when `atomic`), the scene's bindings, the stacks'
/// sizes, and the search: the ray-query loop, or the compute traversal
/// (with the graph traversal where the scene needs it).
fn runtime_part(spec: &KernelSpec, atomic: bool) -> String {
    // Ray queries are a WGSL extension, enabled before anything else.
    let mut out = if spec.ray_query_slots > 0 { String::from("enable wgpu_ray_query;\n") } else { String::new() };
    out.push_str(&prelude(atomic));
    out.push_str(&scene_access(spec.scene_bindings));
    out.push_str(&format!(
        "\nconst RT_BVH_STACK: u32 = {}u;\nconst RT_TLAS_STACK: u32 = {}u;\nconst RT_GROUPS: bool = {};\nconst RT_TRIANGLES_ONLY: bool = {};\nconst RT_CWBVH: bool = {};\nconst RT_CW_STACK: u32 = {}u;\n",
        spec.bvh_stack,
        spec.tlas_stack.max(1),
        spec.tlas_stack > 0,
        spec.triangles_only,
        spec.cwbvh_stack > 0,
        spec.cwbvh_stack.max(1),
    ));
    out.push_str(HITS);
    if spec.ray_query_slots > 0 {
        // The ray-query loop: it defines rt_search.
        out.push_str(KEPT_XFORM);
        out.push_str(&super::rayquery::wgsl::search_wgsl(spec.ray_query_slots));
    } else {
        out.push_str(TRAVERSE);
        if spec.graph_levels > 0 {
            out.push_str(&format!(
                "\nconst RT_LEVELS: u32 = {}u;\nconst RT_GRAPH_STACK: u32 = {}u;\nvar<private> rt_s_payload: u32;\n",
                spec.graph_levels, spec.graph_stack
            ));
            out.push_str(KEPT_XFORM);
            out.push_str(GRAPH);
            out.push_str(MOTION);
        } else {
            out.push_str(TWO_LEVEL);
        }
    }
    out
}

/// The WGSL types and shared functions of `all`, deduplicated by name; two
/// programs with different items of one name are a link conflict.
fn linked_items(all: &[KernelProgram]) -> Result<(Linked, Linked)> {
    let mut types = Linked::new();
    let mut functions = Linked::new();
    for p in all {
        for (table, items) in [(&mut types, p.desc.wgsl_types), (&mut functions, p.desc.wgsl_functions)] {
            for item in items {
                match table.get(item.name) {
                    Some((linked, other)) if linked.text != item.text => {
                        return Err(LinkError::LinkConflict {
                            item: item.name.to_string(),
                            a: other.name,
                            a_location: other.location(),
                            b: p.desc.name,
                            b_location: p.desc.location(),
                        }
                        .into());
                    }
                    Some(_) => {}
                    None => {
                        table.insert(item.name, (item, p.desc));
                    }
                }
            }
        }
    }
    Ok((types, functions))
}

/// Per-payload and per-attribute state, and the functions that report,
/// read and commit attributes.
fn payload_and_attribute_state(
    payloads: &BTreeMap<&str, TypeLayout>,
    attributes: &BTreeMap<&str, TypeLayout>,
) -> String {
    let mut out = String::new();
    out.push_str("\n// ---- payload and attribute state ----\n");
    for w in payloads.keys() {
        out.push_str(&format!("var<private> rt_prd_{w}: {w};\n"));
    }
    for (w, layout) in attributes {
        out.push_str(&format!("var<private> rt_c_attr_{w}: {w};\nvar<private> rt_h_attr_{w}: {w};\n"));
        out.push_str(&triangle_attributes(w, layout));
        out.push_str(&format!(
            "fn rt_report_intersection_{w}(material: u32, attr: ptr<function, {w}>) -> bool {{\n    if !rt_c_ok {{ return false; }}\n    rt_c_attr_{w} = *attr;\n    rt_c_custom = true;\n    return rt_report(material);\n}}\n"
        ));
        out.push_str(&format!(
            "fn rt_cand_attr_{w}() -> {w} {{\n    if rt_c_custom {{ return rt_c_attr_{w}; }}\n    return rt_tri_attr_{w}(rt_s_gi, rt_c_prim, rt_c_bary);\n}}\nfn rt_hit_attr_{w}() -> {w} {{\n    if rt_h_custom {{ return rt_h_attr_{w}; }}\n    return rt_tri_attr_{w}(rt_h_gi, rt_h_prim, rt_h_bary);\n}}\n"
        ));
    }
    out.push_str("fn rt_commit_attributes() {\n");
    for w in attributes.keys() {
        out.push_str(&format!("    rt_h_attr_{w} = rt_c_attr_{w};\n"));
    }
    out.push_str("}\n");
    out.push_str("fn rt_report_intersection(material: u32) -> bool {\n    if !rt_c_ok { return false; }\n    rt_c_custom = true;\n    return rt_report(material);\n}\n");
    out
}

/// The kernel's entry point: per launch index, the ray-generation call
/// `run_ray_generation`, then the exception program after an exception.
fn entry_point(spec: &KernelSpec, run_ray_generation: &str) -> String {
    let ex_call = match (spec.exception, spec.default_exception) {
        (Some(ex), _) => {
            format!("        {}({});\n", ex.desc.wgsl_entry, var_args(ex.desc, "rt_launch.exception.y").join(", "))
        }
        (None, Some(offset)) => {
            format!("        rt_default_exception(rt_load_RtBuffer(rt_launch.ray_generation.y + {offset}u));\n")
        }
        (None, None) => String::new(),
    };
    format!(
        "
@compute @workgroup_size(8, 8, 1)
fn rt_main(@builtin(global_invocation_id) gid: vec3<u32>) {{
    let idx = gid.xy + rt_launch.origin;
    if idx.x >= rt_launch.dim.x || idx.y >= rt_launch.dim.y {{
        return;
    }}
    rt_idx = idx;
    rt_exc = 0u;
    rt_rays = 0u;
    rt_o2w = mat4x4<f32>(vec4<f32>(1.0, 0.0, 0.0, 0.0), vec4<f32>(0.0, 1.0, 0.0, 0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(0.0, 0.0, 0.0, 1.0));
    rt_w2o = rt_o2w;
    {run_ray_generation}
    if rt_exc != 0u {{
        rt_log_exception();
{ex_call}    }}
    if rt_rays != 0u {{
        atomicAdd(&rt_log[2], rt_rays);
    }}
}}
"
    )
}

/// Built-in triangle attributes, filled by field name.
fn triangle_attributes(w: &str, layout: &TypeLayout) -> String {
    let mut body = String::new();
    for f in layout.fields {
        let field = wgsl_field(f.name);
        match TriangleBuiltin::of_field(f) {
            Some(TriangleBuiltin::GeometricNormal) => body.push_str(&format!("    a.{field} = gn;\n")),
            Some(TriangleBuiltin::ShadingNormal) => body.push_str(&format!(
                "    a.{field} = gn;\n    if rt_scene[g + 3u] != RT_NONE {{\n        let nb = rt_scene[g + 3u];\n        a.{field} = rt_v3(nb + i0 * 3u) * w + rt_v3(nb + i1 * 3u) * bary.x + rt_v3(nb + i2 * 3u) * bary.y;\n    }}\n"
            )),
            Some(TriangleBuiltin::Texcoord) => body.push_str(&format!(
                "    a.{field} = bary;\n    if rt_scene[g + 4u] != RT_NONE {{\n        let tb = rt_scene[g + 4u];\n        a.{field} = vec2<f32>(rt_f(tb + i0 * 2u), rt_f(tb + i0 * 2u + 1u)) * w + vec2<f32>(rt_f(tb + i1 * 2u), rt_f(tb + i1 * 2u + 1u)) * bary.x + vec2<f32>(rt_f(tb + i2 * 2u), rt_f(tb + i2 * 2u + 1u)) * bary.y;\n    }}\n"
            )),
            Some(TriangleBuiltin::Barycentrics) => body.push_str(&format!("    a.{field} = bary;\n")),
            None => {}
        }
    }
    format!(
        "fn rt_tri_attr_{w}(gi: u32, prim: u32, bary: vec2<f32>) -> {w} {{
    var a: {w};
    let g = rt_scene[2] + gi * 8u;
    if rt_scene[g] == 1u {{
        return a;
    }}
    let ib = rt_scene[g + 2u] + prim * 3u;
    let i0 = rt_scene[ib];
    let i1 = rt_scene[ib + 1u];
    let i2 = rt_scene[ib + 2u];
    let p0 = rt_tri_corner(g, i0);
    let gn = cross(rt_tri_corner(g, i1) - p0, rt_tri_corner(g, i2) - p0);
    let w = 1.0 - bary.x - bary.y;
{body}    return a;
}}
"
    )
}

/// The WGSL name of a struct field (the compiler suffixes reserved words).
fn wgsl_field(name: &str) -> String {
    if naga_reserved(name) { format!("{name}_") } else { name.to_string() }
}

fn naga_reserved(name: &str) -> bool {
    // Attribute field names the runtime fills are never reserved words; the
    // check guards the general case cheaply.
    matches!(name, "type" | "struct" | "fn" | "let" | "var" | "const" | "loop" | "if" | "else" | "return")
}

fn dispatch_intersection(programs: &[KernelProgram]) -> String {
    let mut cases = Arms::default();
    for p in programs.iter().filter(|p| p.desc.kind == ProgramKind::Intersection) {
        let mut args = Vec::new();
        let mut decl = String::new();
        if let Some(a) = p.desc.attributes {
            decl = format!("var a: {};\n            ", mangle(&a));
            args.push("&a".to_string());
        }
        args.push("prim".to_string());
        args.extend(var_args(p.desc, "vars"));
        cases.add(p.case, format!("            {decl}{}({});\n", p.desc.wgsl_entry, args.join(", ")));
    }
    let cases = cases.render();
    format!(
        "fn rt_isect_dispatch(case_id: u32, vars: u32, prim: u32) {{\n    switch case_id {{\n{cases}        default: {{}}\n    }}\n}}\n"
    )
}

fn dispatch_any_hit(programs: &[KernelProgram]) -> String {
    let mut cases = Arms::default();
    for p in programs.iter().filter(|p| p.desc.kind == ProgramKind::AnyHit) {
        let mut args = Vec::new();
        let mut pre = String::new();
        let mut post = String::new();
        if let Some(pl) = p.desc.payload {
            pre = format!("var p = rt_prd_{};\n            ", pl.wgsl);
            post = format!("\n            rt_prd_{} = p;", pl.wgsl);
            args.push("&p".to_string());
        }
        if let Some(a) = p.desc.attributes {
            args.push(format!("rt_cand_attr_{}()", a.wgsl));
        }
        args.extend(var_args(p.desc, "vars"));
        cases.add(p.case, format!("            {pre}{}({});{post}\n", p.desc.wgsl_entry, args.join(", ")));
    }
    let cases = cases.render();
    format!(
        "fn rt_anyhit_dispatch(case_id: u32, vars: u32) {{\n    switch case_id {{\n{cases}        default: {{}}\n    }}\n}}\n"
    )
}

/// Visit programs: the chosen child, or `RT_NONE`. A visit program whose
/// payload type is not the traced ray's raises the invalid-ray exception
/// (as the CPU backend's argument check does) and chooses nothing.
fn dispatch_visit(programs: &[KernelProgram], payload_ids: &BTreeMap<&str, u32>) -> String {
    let mut cases = Arms::default();
    for p in programs.iter().filter(|p| p.desc.kind == ProgramKind::Visit) {
        let mut args = Vec::new();
        let mut check = String::new();
        if let Some(pl) = p.desc.payload {
            check = format!(
                "if rt_s_payload != {}u {{\n                rt_raise(RT_EXC_INVALID_RAY);\n                return RT_NONE;\n            }}\n            ",
                payload_ids[pl.wgsl]
            );
            args.push(format!("rt_prd_{}", pl.wgsl));
        }
        args.extend(var_args(p.desc, "vars"));
        cases.add(p.case, format!("            {check}return {}({});\n", p.desc.wgsl_entry, args.join(", ")));
    }
    let cases = cases.render();
    format!(
        "fn rt_visit_dispatch(case_id: u32, vars: u32) -> u32 {{\n    switch case_id {{\n{cases}        default: {{}}\n    }}\n    return RT_NONE;\n}}\n"
    )
}

/// Closest-hit and miss dispatch for payload `w` at depth `d`.
fn dispatch_payload(programs: &[KernelProgram], w: &str, d: u32) -> String {
    let mut ch = Arms::default();
    let mut miss = Arms::default();
    for p in programs {
        if p.desc.payload.map(|l| l.wgsl) != Some(w) {
            continue;
        }
        let mut args = vec!["prd".to_string()];
        if let Some(a) = p.desc.attributes {
            args.push(format!("rt_hit_attr_{}()", a.wgsl));
        }
        args.extend(var_args(p.desc, "vars"));
        let body = format!("            {}_d{d}({});\n", p.desc.wgsl_entry, args.join(", "));
        match p.desc.kind {
            ProgramKind::ClosestHit => ch.add(p.case, body),
            ProgramKind::Miss => miss.add(p.case, body),
            _ => {}
        }
    }
    let (ch, miss) = (ch.render(), miss.render());
    format!(
        "fn rt_ch_{w}_d{d}(case_id: u32, vars: u32, prd: ptr<function, {w}>) {{\n    switch case_id {{\n{ch}        default: {{\n            rt_raise(RT_EXC_INVALID_RAY);\n        }}\n    }}\n}}\nfn rt_miss_{w}_d{d}(case_id: u32, vars: u32, prd: ptr<function, {w}>) {{\n    switch case_id {{\n{miss}        default: {{\n            rt_raise(RT_EXC_INVALID_RAY);\n        }}\n    }}\n}}\n"
    )
}

fn trace_function(w: &str, d: u32, note_payload: &str) -> String {
    format!(
        "fn rt_trace_{w}_d{d}(object: u32, ray: RtRay, prd: ptr<function, {w}>, flags: u32, mask: u32) {{
    let time = rt_next_time;
    rt_next_time = 0.0;
    if rt_exc != 0u {{
        return;
    }}
    if !rt_valid_ray(ray) || object >= rt_scene[7] || ray.ray_type >= rt_scene[4] {{
        rt_raise(RT_EXC_INVALID_RAY);
        return;
    }}
    let saved_ray = rt_ray;
    let saved_t = rt_t;
    let saved_time = rt_time;
    rt_time = time;
    let saved_prim = rt_prim;
    let saved_o2w = rt_o2w;
    let saved_w2o = rt_w2o;
    let saved_rs = vec3<u32>(rt_hk, rt_rflags, rt_rmask);
    let saved_ic = rt_icur;
    rt_rflags = flags;
    rt_rmask = mask & 0xffu;
    rt_rays = rt_rays + 1u;{note_payload}
    rt_prd_{w} = *prd;
    rt_search(object, ray, flags, mask);
    *prd = rt_prd_{w};
    if rt_h_found {{
        let rec = rt_enter_hit(ray, flags);
        if rec != RT_NONE {{
            rt_ch_{w}_d{d}(rt_scene[rec], rt_scene[rec + 1u], prd);
        }}
    }} else {{
        let mr = rt_scene[5] + ray.ray_type * 2u;
        rt_ray = ray;
        rt_hk = 0u;
        if rt_scene[mr] != 0u {{
            rt_miss_{w}_d{d}(rt_scene[mr], rt_scene[mr + 1u], prd);
        }}
    }}
    rt_ray = saved_ray;
    rt_t = saved_t;
    rt_time = saved_time;
    rt_prim = saved_prim;
    rt_o2w = saved_o2w;
    rt_w2o = saved_w2o;
    rt_hk = saved_rs.x;
    rt_rflags = saved_rs.y;
    rt_rmask = saved_rs.z;
    rt_icur = saved_ic;
}}
"
    )
}

#[cfg(test)]
mod tests {
    use rt_std::program::{FieldLayout, LayoutKind, ScalarKind, TypeLayout};

    const VEC2: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 2 };
    const VEC3: LayoutKind = LayoutKind::Vector { scalar: ScalarKind::F32, len: 3 };

    /// The megakernel fills the built-in triangle attributes by the same
    /// rule as the CPU backend: by name, and by type as written or as a path.
    #[test]
    fn triangle_attributes_are_filled_by_name_and_type() {
        static FIELDS: [FieldLayout; 4] = [
            FieldLayout { name: "geometric_normal", ty: "Vec3", kind: VEC3, offset_words: 0 },
            FieldLayout { name: "texcoord", ty: "glam :: Vec2", kind: VEC2, offset_words: 3 },
            FieldLayout { name: "barycentrics", ty: "Vec3", kind: VEC3, offset_words: 5 },
            FieldLayout { name: "weight", ty: "f32", kind: LayoutKind::Scalar(ScalarKind::F32), offset_words: 8 },
        ];
        let layout = TypeLayout {
            kind: rt_std::program::LayoutKind::Struct,
            rust: "Mixed",
            wgsl: "Mixed",
            words: 9,
            fields: &FIELDS,
        };
        let wgsl = super::triangle_attributes("Mixed", &layout);
        assert!(wgsl.contains("a.geometric_normal = gn;"), "{wgsl}");
        assert!(wgsl.contains("a.texcoord = bary;"), "{wgsl}");
        // A Vec3 named `barycentrics` is not the Vec2 built-in, and other
        // fields stay as `var a` starts them: zero.
        assert!(!wgsl.contains("a.barycentrics"), "{wgsl}");
        assert!(!wgsl.contains("a.weight"), "{wgsl}");
    }
}
