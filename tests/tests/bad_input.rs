//! Bad input, never a panic: each case asserts the error kind and message
//! (the file and line, the handle, the variable at fault), and a bounded
//! mutation fuzzer checks that mesh loading and scene building fail cleanly
//! on anything.

use examples::mesh::parse_obj;
use glam::{Mat4, Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::meshes::unit_quad;

#[rt_payload]
pub struct Prd {
    pub color: Vec3,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>, #[var] gain: f32) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Prd { color: Vec3::ZERO };
    rt_trace(top, Ray::new(vec3(p.x, p.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
    out[idx] = (prd.color * gain).extend(1.0);
}

#[rt_program(closest_hit)]
pub fn white(prd: &mut Prd) {
    prd.color = Vec3::ONE;
}

#[rt_program(miss)]
pub fn black(prd: &mut Prd) {
    prd.color = Vec3::ZERO;
}

fn mesh_error(text: &str) -> String {
    parse_obj(text, "bad.obj", None).map(|_| ()).expect_err("must be refused").to_string()
}

fn scene(backend: Backend, mesh: TriangleMesh) -> (Context, BufferId) {
    let (ctx, out, _) = scene_of(backend, mesh);
    (ctx, out)
}

/// `scene`, with the mesh's geometry.
fn scene_of(backend: Backend, mesh: TriangleMesh) -> (Context, BufferId, GeometryId) {
    let mut ctx = Context::new();
    ctx.set_backend(backend);
    let rg = ctx.create_program(&camera::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&black::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let g = ctx.create_triangles(mesh).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&white::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 8, 8).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "gain", 1.0f32).unwrap();
    (ctx, out, g)
}

// ---- OBJ and MTL ----

#[test]
fn obj_malformed_number() {
    assert_eq!(
        mesh_error("v 1 x 2\nv 0 0 0\nv 1 1 1\nf 1 2 3\n"),
        "bad.obj:1: a vertex has `x`, which is not a number"
    );
}

#[test]
fn obj_truncated_vertex() {
    let e = mesh_error("v 0 0 0\nv 1 0 0\nv 1 1\nf 1 2 3\n");
    assert!(e.starts_with("bad.obj:3: ") && e.contains("needs 3 numbers, found 2"), "{e}");
}

#[test]
fn obj_face_with_two_vertices() {
    assert_eq!(mesh_error("v 0 0 0\nv 1 0 0\nf 1 2\n"), "bad.obj:3: a face needs at least 3 vertices, this one has 2");
}

#[test]
fn obj_index_zero() {
    let e = mesh_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n");
    assert!(e.starts_with("bad.obj:4: ") && e.contains("index 0 is invalid (OBJ indices start at 1)"), "{e}");
}

#[test]
fn obj_index_out_of_range() {
    let e = mesh_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n");
    assert!(e.starts_with("bad.obj:4: ") && e.contains("index 9 is out of range"), "{e}");
}

#[test]
fn obj_negative_index_out_of_range() {
    let e = mesh_error("v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -7\n");
    assert!(e.starts_with("bad.obj:4: ") && e.contains("out of range"), "{e}");
}

#[test]
fn obj_nan_vertex() {
    let e = mesh_error("v 0 0 0\nv nan 0 0\nv 1 1 0\nf 1 2 3\n");
    assert!(e.starts_with("bad.obj:2: ") && e.contains("non-finite"), "{e}");
}

#[test]
fn obj_infinite_vertex() {
    let e = mesh_error("v 0 0 0\nv 1 inf 0\nv 1 1 0\nf 1 2 3\n");
    assert!(e.starts_with("bad.obj:2: ") && e.contains("non-finite"), "{e}");
}

#[test]
fn obj_without_faces_is_empty() {
    let e = mesh_error("v 0 0 0\nv 1 0 0\nv 1 1 0\n");
    assert!(e.starts_with("bad.obj") && e.contains("no triangles") || e.contains("empty"), "{e}");
}

#[test]
fn obj_empty_file() {
    let e = mesh_error("");
    assert!(e.starts_with("bad.obj"), "{e}");
}

#[test]
fn mtl_missing_is_a_warning_with_default_material() {
    let m = parse_obj("mtllib nowhere.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", "ok.obj", None).unwrap();
    assert_eq!(m.warnings.len(), 1, "{:?}", m.warnings);
    assert!(m.warnings[0].contains("nowhere.mtl") && m.warnings[0].contains("default grey"), "{:?}", m.warnings);
}

#[test]
fn mtl_malformed_is_a_warning_too() {
    let dir = std::env::temp_dir().join(format!("rt-bad-mtl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("bad.mtl"), "newmtl red\nKd 1 oops 0\n").unwrap();
    let r = parse_obj("mtllib bad.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", "m.obj", Some(&dir));
    let _ = std::fs::remove_dir_all(&dir);
    match r {
        Ok(m) => assert!(m.warnings.iter().any(|w| w.contains("bad.mtl")), "{:?}", m.warnings),
        Err(e) => assert!(e.to_string().contains("bad.mtl"), "{e}"),
    }
}

// ---- geometry ----

fn geometry_error(mesh: TriangleMesh) -> String {
    Context::new().create_triangles(mesh).map(|_| ()).expect_err("must be refused").to_string()
}

#[test]
fn triangles_empty() {
    assert_eq!(geometry_error(TriangleMesh::default()), "geometry 0: the mesh has no triangles");
}

#[test]
fn triangles_index_out_of_range() {
    let mut m = unit_quad();
    m.indices[1] = [0, 2, 4];
    assert_eq!(geometry_error(m), "geometry 0: triangle 1 uses vertex 4, but there are 4 vertices");
}

#[test]
fn triangles_nan_position() {
    let mut m = unit_quad();
    m.positions[2].y = f32::NAN;
    assert!(geometry_error(m).starts_with("geometry 0: vertex 2 has a non-finite position"));
}

#[test]
fn moving_vertices_to_bad_positions_is_refused_and_loses_nothing() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let (mut ctx, out, g) = scene_of(backend, unit_quad());
        ctx.launch(0, 8, 8).unwrap();
        let before = ctx.read_buffer::<Vec4>(out).unwrap();
        let mut moved = unit_quad().positions;
        moved[3].x = f32::INFINITY;
        let err = ctx.set_triangle_positions(g, moved).unwrap_err().to_string();
        assert!(err.starts_with("geometry 0: vertex 3 has a non-finite position"), "{err}");
        let err = ctx.set_triangle_positions(g, vec![Vec3::ZERO; 3]).unwrap_err().to_string();
        assert_eq!(err, "geometry 0: 3 positions given for 4 vertices; create a new geometry to change topology");
        // The mesh is as it was: the same image, and no refit.
        ctx.launch(0, 8, 8).unwrap();
        assert_eq!(ctx.read_buffer::<Vec4>(out).unwrap(), before);
        assert_eq!(ctx.acceleration_builds().1, 0, "refits on {backend:?}");
    }
}

#[test]
fn triangles_normal_count() {
    let mut m = unit_quad();
    m.normals = Some(vec![Vec3::Z; 3]);
    assert_eq!(geometry_error(m), "geometry 0: 3 normals for 4 vertices");
}

#[test]
fn triangles_material_index_count() {
    let mut m = unit_quad();
    m.material_indices = Some(vec![0]);
    assert_eq!(geometry_error(m), "geometry 0: 1 material indices for 2 triangles");
}

#[test]
fn degenerate_triangles_are_accepted_and_never_hit() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let mut m = unit_quad();
        // A zero-area sliver and a triangle with repeated vertices, covering
        // the whole view.
        m.positions.extend([Vec3::new(-9.0, -9.0, 1.0), Vec3::new(9.0, 9.0, 1.0), Vec3::new(0.0, 0.0, 1.0)]);
        m.indices = vec![[4, 5, 6], [4, 4, 5]];
        let (mut ctx, out) = scene(backend, m);
        let r = ctx.launch(0, 8, 8).unwrap();
        assert!(r.exceptions.is_empty());
        assert!(ctx.read_buffer::<Vec4>(out).unwrap().iter().all(|c| c.truncate() == Vec3::ZERO), "{backend:?}");
    }
}

#[test]
fn singular_transform() {
    let mut ctx = Context::new();
    let g = ctx.create_triangles(unit_quad()).unwrap();
    let m = ctx.create_material();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
    let e = ctx.create_transform(Mat4::from_scale(Vec3::new(1.0, 0.0, 1.0)), gg).unwrap_err().to_string();
    assert!(e.starts_with("transform: the matrix is singular or not finite"), "{e}");
}

#[test]
fn geometry_instance_without_materials() {
    let mut ctx = Context::new();
    let g = ctx.create_triangles(unit_quad()).unwrap();
    assert_eq!(
        ctx.create_geometry_instance(g, &[]).unwrap_err().to_string(),
        "geometry 0: a geometry instance needs at least one material"
    );
}

#[test]
fn kd_tree_builder_is_refused_by_name() {
    let (mut ctx, _) = scene(Backend::Cpu, unit_quad());
    let g = ctx.create_triangles(unit_quad()).unwrap();
    let m = ctx.create_material();
    let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
    let gg = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::TriangleKdTree)).unwrap();
    ctx.set_var(Scope::Context, "top", gg).unwrap();
    let e = ctx.launch(0, 8, 8).unwrap_err().to_string();
    assert!(e.starts_with("acceleration builder `TriangleKdTree` cannot be honoured: obvhs builds BVHs"), "{e}");
}

// ---- launches, programs, variables, buffers ----

#[test]
fn zero_size_launch() {
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let (mut ctx, _) = scene(backend, unit_quad());
        let e = ctx.launch(0, 0, 8).unwrap_err();
        assert_eq!(e.to_string(), "launch of 0x8: a launch needs at least one index in each dimension");
    }
}

#[test]
fn launching_before_programs_are_set() {
    let mut ctx = Context::new();
    assert_eq!(ctx.launch(0, 4, 4).unwrap_err().to_string(), "entry point 0 has no ray generation program");
    assert_eq!(
        ctx.launch(3, 4, 4).unwrap_err().to_string(),
        "entry point 3 does not exist: the context has 1 (see `set_entry_point_count`)"
    );
}

#[test]
fn variable_set_with_the_wrong_type() {
    let (mut ctx, _) = scene(Backend::Cpu, unit_quad());
    ctx.set_var(Scope::Context, "gain", Vec3::ONE).unwrap();
    let e = ctx.launch(0, 8, 8).unwrap_err().to_string();
    assert!(
        e.contains("variable `gain` of program `camera`")
            && e.contains("declared `f32`, but the context scope sets it to `Vec3`"),
        "{e}"
    );
}

#[test]
fn buffer_of_the_wrong_element_type_for_a_variable() {
    let (mut ctx, _) = scene(Backend::Cpu, unit_quad());
    let wrong = ctx.create_buffer_2d::<f32>(BufferType::Output, 8, 8).unwrap();
    ctx.set_var(Scope::Context, "out", wrong).unwrap();
    let e = ctx.launch(0, 8, 8).unwrap_err().to_string();
    assert!(
        e.contains("variable `out`")
            && e.contains("declared `RwBuffer2d<Vec4>`")
            && e.contains("RwBuffer2d<f32> (Output)"),
        "{e}"
    );
}

#[test]
fn input_buffer_where_the_program_writes() {
    let (mut ctx, _) = scene(Backend::Cpu, unit_quad());
    let input = ctx.create_buffer_2d::<Vec4>(BufferType::Input, 8, 8).unwrap();
    ctx.set_var(Scope::Context, "out", input).unwrap();
    let e = ctx.launch(0, 8, 8).unwrap_err().to_string();
    assert!(e.contains("Buffer2d<Vec4> (Input)"), "{e}");
}

#[test]
fn program_in_the_wrong_slot() {
    let mut ctx = Context::new();
    let ch = ctx.create_program(&white::PROGRAM);
    let e = ctx.set_ray_generation_program(0, ch).unwrap_err().to_string();
    assert!(
        e.starts_with("`white` (")
            && e.ends_with("is a ClosestHit program, but entry point 0's ray generation takes a RayGeneration program"),
        "{e}"
    );
}

#[test]
fn ray_type_out_of_range() {
    let mut ctx = Context::new();
    let miss = ctx.create_program(&black::PROGRAM);
    assert_eq!(
        ctx.set_miss_program(4, miss).unwrap_err().to_string(),
        "ray type 4 does not exist: the context has 1 (see `set_ray_type_count`)"
    );
}

#[test]
fn handle_from_another_context() {
    let mut other = Context::new();
    for _ in 0..5 {
        other.create_material();
    }
    let foreign = other.create_material();
    let mut ctx = Context::new();
    let g = ctx.create_triangles(unit_quad()).unwrap();
    assert_eq!(
        ctx.create_geometry_instance(g, &[foreign]).unwrap_err().to_string(),
        "MaterialId(5) is not a valid handle of this context"
    );
}

#[test]
fn buffer_reads_and_writes_check_type_and_length() {
    let mut ctx = Context::new();
    let b = ctx.create_buffer(BufferType::Input, vec![1.0f32, 2.0]);
    assert_eq!(ctx.read_buffer::<u32>(b).unwrap_err().to_string(), "buffer 0: holds `f32`, not `u32`");
    assert_eq!(
        ctx.write_buffer(b, &[1.0f32]).unwrap_err().to_string(),
        "buffer 0: 1 elements written to a buffer of 2"
    );
    let e = ctx.create_buffer_2d::<f32>(BufferType::Output, 1 << 20, 1 << 20).unwrap_err().to_string();
    assert!(e.contains("do not fit in 32-bit indices"), "{e}");
}

#[test]
fn sampler_with_the_wrong_texel_count() {
    let mut ctx = Context::new();
    let e = ctx.create_sampler(vec![Vec4::ONE; 3], 2, 2, WrapMode::Repeat, FilterMode::Linear).unwrap_err().to_string();
    assert_eq!(e, "buffer 0: 3 texels for a 2x2 texture");
}

#[test]
fn textures_of_unsupported_formats_and_bad_files() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-bad-textures");
    std::fs::create_dir_all(&dir).unwrap();
    let mut ctx = Context::new();
    let mut load = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let e = ctx.create_sampler_from_file(&path, WrapMode::Repeat, FilterMode::Linear).unwrap_err();
        assert!(matches!(e, RtError::Io(IoError::Texture { .. })), "{e:?}");
        e.to_string().replace(&dir.display().to_string(), "DIR")
    };
    // A JPEG's signature: a real format, but not one this build reads.
    assert_eq!(
        load("photo.jpg", &[0xFF, 0xD8, 0xFF, 0xE0, 0, 0x10, b'J', b'F', b'I', b'F', 0]),
        "texture DIR/photo.jpg: JPG images are not supported (supported: PNG, Radiance HDR)"
    );
    assert_eq!(
        load("notes.txt", b"just some text"),
        "texture DIR/notes.txt: not an image format this build reads (PNG, Radiance HDR)"
    );
    // A PNG cut off after its signature and part of the header.
    let e = load("cut.png", &[0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, b'I', b'H']);
    assert!(e.starts_with("texture DIR/cut.png: does not decode as Png: "), "{e}");
    let e = ctx
        .create_sampler_from_file(dir.join("missing.png"), WrapMode::Repeat, FilterMode::Linear)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("texture ") && e.contains("missing.png: "), "{e}");
    // A good one still loads, texels in [0, 1].
    let path = dir.join("ok.png");
    image::RgbaImage::from_pixel(2, 1, image::Rgba([255, 0, 0, 255])).save(&path).unwrap();
    ctx.create_sampler_from_file(&path, WrapMode::Repeat, FilterMode::Linear).unwrap();
}

#[test]
fn device_lost_mid_launch_loses_nothing() {
    let (mut ctx, out) = scene(Backend::Wgpu, unit_quad());
    ctx.launch(0, 8, 8).unwrap();
    let before: Vec<Vec4> = ctx.read_buffer(out).unwrap();
    assert!(before.iter().any(|p| p.x == 1.0), "the quad is hit");
    // A changed variable: a launch that completed would change the image.
    ctx.set_var(Scope::Context, "gain", 0.5f32).unwrap();
    ctx.simulate_device_loss_in_next_launch();
    let e = ctx.launch(0, 8, 8).unwrap_err();
    assert!(matches!(e, RtError::Device(DeviceError::DeviceLost { .. })), "{e:?}");
    let text = e.to_string();
    assert!(
        text.starts_with("the wgpu device on ")
            && text.contains("was lost during the launch (")
            && text.ends_with(
                "the launch wrote none of its outputs and the context's data is unchanged: the next launch opens a new device and uploads the scene again"
            ),
        "{text}"
    );
    assert_eq!(ctx.read_buffer::<Vec4>(out).unwrap(), before, "outputs untouched by the lost launch");
    // The next launch runs on a new device and matches the CPU backend.
    ctx.launch(0, 8, 8).unwrap();
    let after: Vec<Vec4> = ctx.read_buffer(out).unwrap();
    let (mut cpu, cpu_out) = scene(Backend::Cpu, unit_quad());
    cpu.set_var(Scope::Context, "gain", 0.5f32).unwrap();
    cpu.launch(0, 8, 8).unwrap();
    assert_eq!(after, cpu.read_buffer::<Vec4>(cpu_out).unwrap());
    assert!(after.iter().any(|p| p.x == 0.5));
}

// ---- bounded fuzzing of mesh loading and scene building ----

/// A tiny deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

#[test]
fn mutated_obj_files_never_panic() {
    let seed_text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/scenes/cornell_box.obj")).unwrap();
    let tokens = [
        "v", "f", "vn", "vt", "nan", "inf", "-1", "0", "99999", "1e39", "/", "//", " ", "\n", "#", "o", "g", "usemtl x",
    ];
    let iterations: usize = std::env::var("RT_FUZZ_MESH").ok().and_then(|v| v.parse().ok()).unwrap_or(400);
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let mut built = 0;
    for _ in 0..iterations {
        let mut text: Vec<u8> = seed_text.as_bytes().to_vec();
        for _ in 0..1 + rng.below(6) {
            let at = rng.below(text.len() + 1);
            match rng.below(3) {
                0 => {
                    let t = tokens[rng.below(tokens.len())];
                    text.splice(at..at, t.bytes());
                }
                1 => {
                    let end = (at + rng.below(12)).min(text.len());
                    text.drain(at..end);
                }
                _ => {
                    if at < text.len() {
                        text[at] = b"0123456789 -.ef/\n"[rng.below(17)];
                    }
                }
            }
        }
        let Ok(text) = String::from_utf8(text) else { continue };
        if let Ok(loaded) = parse_obj(&text, "fuzz.obj", None) {
            // Whatever loads must build and launch cleanly.
            let (mut ctx, _) = scene(Backend::Cpu, unit_quad());
            if let Ok(g) = ctx.create_triangles(loaded.mesh) {
                let m = ctx.create_material();
                let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
                let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
                ctx.set_var(Scope::Context, "top", gg).unwrap();
                ctx.launch(0, 4, 4).unwrap();
                built += 1;
            }
        }
    }
    assert!(built > 0, "no mutant loaded: the fuzzer explores nothing");
}

/// The box `[lo, hi]` from the variables, as given (NaN, inverted).
#[rt_program(bounding_box)]
pub fn given_box(prim: u32, #[var] lo: Vec3, #[var] hi: Vec3) -> Aabb {
    let _ = prim;
    Aabb::new(lo, hi)
}

#[rt_program(intersection)]
pub fn never_hits(prim: u32) {
    let _ = prim;
}

/// A bounding-box program returning a NaN, an infinite or an inverted box:
/// a typed error naming the program, its file and line, the geometry and
/// the primitive on every target (the CPU backend, the compute traversal,
/// ray queries), never a panic or a device loss; fixed, the next launch
/// works.
#[test]
fn a_bounding_box_program_returning_no_box_is_an_error_naming_it() {
    use rt_tests::targets::On;
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (mut ctx, _) = scene(on.backend, unit_quad());
        ctx.set_traversal(on.traversal);
        let isect = ctx.create_program(&never_hits::PROGRAM);
        let bounds = ctx.create_program(&given_box::PROGRAM);
        let geom = ctx.create_custom_geometry(3, isect, bounds).unwrap();
        let mat = ctx.create_material();
        let gi = ctx.create_geometry_instance(geom, &[mat]).unwrap();
        for (lo, hi, problem) in [
            (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::ONE, "a NaN bound"),
            (Vec3::ZERO, Vec3::new(1.0, f32::INFINITY, 1.0), "an infinite bound"),
            (Vec3::ZERO, Vec3::new(1.0, -1.0, 1.0), "min above max"),
        ] {
            ctx.set_var(geom, "lo", lo).unwrap();
            ctx.set_var(geom, "hi", hi).unwrap();
            // A fresh geometry group each time: bounds are read when a
            // group's tree is built.
            let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
            ctx.set_var(Scope::Context, "top", gg).unwrap();
            let err = ctx.launch(0, 4, 4).unwrap_err();
            let RtError::Scene(SceneError::BadBounds { program, location, geometry, primitive, .. }) = &err else {
                panic!("{}: expected BadBounds, got {err:?}", on.name());
            };
            assert_eq!((*program, *geometry, *primitive), ("given_box", geom.index(), 0), "{}", on.name());
            assert!(location.contains("bad_input.rs:"), "{location}");
            assert!(err.to_string().contains(problem), "{}: {err}", on.name());
        }
        ctx.set_var(geom, "lo", Vec3::ZERO).unwrap();
        ctx.set_var(geom, "hi", Vec3::ONE).unwrap();
        let gg = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", gg).unwrap();
        ctx.launch(0, 4, 4).unwrap_or_else(|e| panic!("{}: {e}", on.name()));
    }
}
