//! Bindless buffers (`BindlessBuffer<T>`, `RwBindlessBuffer<T>`; OptiX
//! `rtBufferId`, `rtBufferGetId`): ids held in a `#[var]`, a buffer of ids,
//! a struct field and a payload field, read (and written) through on every
//! target with exact values; per-mesh colours read from a closest hit
//! through a buffer of ids indexed by a geometry instance's variable; an
//! index out of bounds through an id raises
//! `EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS`, a null id, an id of no buffer
//! and an id of a buffer of another element type raise
//! `EXCEPTION_BUFFER_ID_INVALID`; the host's and the launch's checks name
//! the buffer, the variable and both types.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_struct]
pub struct Table {
    pub data: BindlessBuffer<f32>,
    pub scale: f32,
}

/// Launch index `i` reads entry `i % 5` of `ids` at index `i / 5`, and
/// through the other ids as the test says.
#[allow(clippy::too_many_arguments)]
#[rt_program(ray_generation)]
pub fn read_through_ids(
    #[var] first: BindlessBuffer<u32>,
    #[var] ids: Buffer<BindlessBuffer<u32>>,
    #[var] table: Table,
    #[var] sink: RwBindlessBuffer<u32>,
    #[var] base: u32,
    #[var] mut out: RwBuffer<u32>,
    #[var] mut floats: RwBuffer<f32>,
    #[var] mut echoed: RwBuffer<BindlessBuffer<u32>>,
) {
    let i = launch_index().x;
    let b = ids[i % 5];
    let mut len = b.len();
    if b == first {
        len += 100;
    }
    out[i * 3] = b.load(i / 5);
    out[i * 3 + 1] = len;
    // An id made in the program from a `u32`: the same buffers.
    let made = BindlessBuffer::<u32>::from_id(base + i % 2);
    out[i * 3 + 2] = made[0] + made.len() * 1000;
    floats[i] = table.data[i % 2] * table.scale;
    sink.store(i, i * 7 + sink.load(i));
    let none: BindlessBuffer<u32> = BindlessBuffer::NONE;
    echoed[i] = b;
    if b == none || b == BindlessBuffer::default() {
        echoed[i] = first;
    }
}

const N: u32 = 15;

struct Outcome {
    out: Vec<u32>,
    floats: Vec<f32>,
    sunk: Vec<u32>,
    echoed: Vec<u32>,
    exceptions: Vec<(u32, u32)>,
}

fn run_reads(on: On, id_exceptions: bool) -> Outcome {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    ctx.set_exception_enabled(ExceptionKind::BufferIdInvalid, id_exceptions);
    let a = ctx.create_buffer::<u32>(BufferType::Input, vec![10, 11, 12]);
    let b = ctx.create_buffer::<u32>(BufferType::Input, vec![20, 21]);
    let f = ctx.create_buffer::<f32>(BufferType::Input, vec![1.5, 2.5]);
    let sunk = ctx.create_buffer::<u32>(BufferType::InputOutput, (0..N).map(|i| i * 1000).collect());
    let a_id = ctx.buffer_id::<u32>(a).unwrap();
    let b_id = ctx.buffer_id::<u32>(b).unwrap();
    let f_id = ctx.buffer_id::<f32>(f).unwrap();
    // Entries: a, b, none, the f32 buffer read as u32s (another element
    // type), and an id of no buffer.
    let entries =
        vec![a_id, b_id, BindlessBuffer::NONE, BindlessBuffer::from_id(f_id.id()), BindlessBuffer::from_id(99)];
    let ids = ctx.create_buffer(BufferType::Input, entries);
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3 * N as usize]);
    let floats = ctx.create_buffer::<f32>(BufferType::Output, vec![0.0; N as usize]);
    let echoed = ctx.create_buffer(BufferType::Output, vec![BindlessBuffer::<u32>::from_id(77); N as usize]);
    ctx.set_var(Scope::Context, "first", a_id).unwrap();
    ctx.set_var(Scope::Context, "ids", ids).unwrap();
    ctx.set_var(Scope::Context, "table", Table { data: f_id, scale: 2.0 }).unwrap();
    ctx.set_var(Scope::Context, "sink", ctx.rw_buffer_id::<u32>(sunk).unwrap()).unwrap();
    ctx.set_var(Scope::Context, "base", a_id.id()).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "floats", floats).unwrap();
    ctx.set_var(Scope::Context, "echoed", echoed).unwrap();
    let rg = ctx.create_program(&read_through_ids::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, N).unwrap();
    let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    exceptions.sort();
    let echoed = ctx.read_buffer::<BindlessBuffer<u32>>(echoed).unwrap().iter().map(|b| b.id()).collect();
    Outcome {
        out: ctx.read_buffer(out).unwrap(),
        floats: ctx.read_buffer(floats).unwrap(),
        sunk: ctx.read_buffer(sunk).unwrap(),
        echoed,
        exceptions,
    }
}

#[test]
fn ids_in_variables_buffers_and_structs_read_the_same_on_every_target() {
    let (a, b, f) = ([10u32, 11, 12], [20u32, 21], [1.5f32, 2.5]);
    let (a_id, b_id) = (1, 2);
    for id_exceptions in [true, false] {
        let mut want = Vec::new();
        let mut raised = Vec::new();
        let mut want_echoed = Vec::new();
        for i in 0..N {
            let (k, j) = (i % 5, (i / 5) as usize);
            let (value, len) = match k {
                0 => (a[j], 3 + 100),
                // Index 2 is past b's end.
                1 if j < b.len() => (b[j], 2),
                1 => {
                    raised.push((i, EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS));
                    (0, 2)
                }
                _ => {
                    if id_exceptions {
                        raised.push((i, EXCEPTION_BUFFER_ID_INVALID));
                    }
                    (0, 0)
                }
            };
            // `made` alternates between a (3 long) and b (2 long).
            let made = if i % 2 == 0 { a[0] + 3000 } else { b[0] + 2000 };
            want.extend([value, len, made]);
            want_echoed.push([a_id, b_id, a_id, 3, 99][k as usize]);
        }
        let want_floats: Vec<f32> = (0..N).map(|i| f[i as usize % 2] * 2.0).collect();
        let want_sunk: Vec<u32> = (0..N).map(|i| i * 1000 + i * 7).collect();
        for on in On::ALL.into_iter().filter(|on| on.available()) {
            let got = run_reads(on, id_exceptions);
            let name = format!("{} (id exceptions {id_exceptions})", on.name());
            assert_eq!(got.out, want, "{name}");
            assert_eq!(got.floats, want_floats, "{name}");
            assert_eq!(got.sunk, want_sunk, "{name}");
            assert_eq!(got.echoed, want_echoed, "{name}");
            assert_eq!(got.exceptions, raised, "{name}");
        }
    }
}

#[rt_payload]
pub struct Shade {
    pub colour: Vec3,
    pub len: u32,
    pub source: BindlessBuffer<Vec3>,
}

/// Seven rays: two per quad (its triangle 0, then 1), then one that misses.
#[rt_program(ray_generation)]
pub fn shoot(#[var] top: Object, #[var] mut colours_out: RwBuffer<Vec3>, #[var] mut info: RwBuffer<u32>) {
    let i = launch_index().x;
    let cx = (i / 2) as f32 * 3.0 - 3.0;
    let mut d = vec2(0.5, -0.5);
    if i % 2 == 1 {
        d = vec2(-0.5, 0.5);
    }
    let mut prd = Shade { colour: vec3(-1.0, -1.0, -1.0), len: 0, source: BindlessBuffer::NONE };
    rt_trace(top, Ray::new(vec3(cx + d.x, d.y, 5.0), vec3(0.0, 0.0, -1.0), 0, 0.0, 100.0), &mut prd);
    colours_out[i * 2] = prd.colour;
    // The id the payload brought back, read here: the mesh's first colour.
    colours_out[i * 2 + 1] = prd.source[0];
    info[i * 2] = prd.len;
    info[i * 2 + 1] = prd.source.id();
}

/// The colour of the hit triangle, from the buffer of the instance's mesh:
/// `colours` holds one id per mesh, `mesh` (a geometry instance's
/// variable) says which.
#[rt_program(closest_hit)]
pub fn mesh_colour(prd: &mut Shade, #[var] mesh: u32, #[var] colours: Buffer<BindlessBuffer<Vec3>>) {
    let per_mesh = colours[mesh];
    prd.colour = per_mesh.load(primitive_index());
    prd.len = per_mesh.len();
    prd.source = per_mesh;
}

#[rt_program(miss)]
pub fn sky(prd: &mut Shade) {
    prd.colour = vec3(0.0, 0.0, 9.0);
}

fn quad_at(cx: f32) -> TriangleMesh {
    let mut quad = rt_tests::meshes::unit_quad();
    for p in &mut quad.positions {
        p.x += cx;
    }
    quad
}

fn run_scene(on: On) -> (Vec<Vec3>, Vec<u32>, Vec<(u32, u32)>) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(1);
    let per_mesh = [
        vec![Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)],
        vec![Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 1.0, 0.0)],
        // One colour for two triangles: triangle 1 reads past the end.
        vec![Vec3::splat(0.5)],
    ];
    let ids: Vec<BindlessBuffer<Vec3>> = per_mesh
        .into_iter()
        .map(|c| {
            let b = ctx.create_buffer(BufferType::Input, c);
            ctx.buffer_id::<Vec3>(b).unwrap()
        })
        .collect();
    let colours = ctx.create_buffer(BufferType::Input, ids);
    ctx.set_var(Scope::Context, "colours", colours).unwrap();
    let m = ctx.create_material();
    let ch = ctx.create_program(&mesh_colour::PROGRAM);
    ctx.set_closest_hit_program(m, 0, ch).unwrap();
    // The quads at x = -3, 0, 3 draw from meshes 1, 2 and 0.
    let mut instances = Vec::new();
    for (cx, mesh) in [(-3.0, 1u32), (0.0, 2), (3.0, 0)] {
        let g = ctx.create_triangles(quad_at(cx)).unwrap();
        let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
        ctx.set_var(gi, "mesh", mesh).unwrap();
        instances.push(gi);
    }
    let top = ctx.create_geometry_group(&instances, Acceleration::default()).unwrap();
    ctx.set_var(Scope::Context, "top", top).unwrap();
    let colours_out = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::splat(7.0); 14]);
    let info = ctx.create_buffer::<u32>(BufferType::Output, vec![77; 14]);
    ctx.set_var(Scope::Context, "colours_out", colours_out).unwrap();
    ctx.set_var(Scope::Context, "info", info).unwrap();
    let rg = ctx.create_program(&shoot::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&sky::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    let report = ctx.launch_1d(0, 7).unwrap();
    let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    exceptions.sort();
    (ctx.read_buffer(colours_out).unwrap(), ctx.read_buffer(info).unwrap(), exceptions)
}

#[test]
fn a_closest_hit_reads_each_meshs_colours_through_a_buffer_of_ids_on_every_target() {
    let (red, green, blue, yellow, grey) = (
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::splat(0.5),
    );
    // Per ray: the hit colour and the first colour of its mesh (through the
    // payload's id). Buffer ids: mesh 0's is 1, mesh 1's 2, mesh 2's 3.
    let want_colours = vec![
        blue,
        blue,
        yellow,
        blue,
        grey,
        grey,
        // Past the end of mesh 2's one colour: zero.
        Vec3::ZERO,
        grey,
        red,
        red,
        green,
        red,
        // The miss: its colour; the payload's id is none.
        Vec3::new(0.0, 0.0, 9.0),
        Vec3::ZERO,
    ];
    let want_info = vec![2, 2, 2, 2, 1, 3, 1, 3, 2, 1, 2, 1, 0, 0];
    let want_exceptions = vec![(3, EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS), (6, EXCEPTION_BUFFER_ID_INVALID)];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (colours, info, exceptions) = run_scene(on);
        assert_eq!(colours, want_colours, "{}", on.name());
        assert_eq!(info, want_info, "{}", on.name());
        assert_eq!(exceptions, want_exceptions, "{}", on.name());
    }
}

#[rt_program(ray_generation)]
pub fn read_one(#[var] data: BindlessBuffer<u32>, #[var] mut out: RwBuffer<u32>) {
    out[0] = data[0];
}

#[rt_program(ray_generation)]
pub fn write_one(#[var] data: RwBindlessBuffer<u32>) {
    data.store(0, 5);
}

#[test]
fn ids_of_another_element_type_or_of_no_buffer_are_refused_naming_the_buffer_and_variable() {
    let mut ctx = Context::new();
    ctx.set_ray_type_count(0);
    let floats = ctx.create_buffer::<f32>(BufferType::Input, vec![1.0]);
    let e = ctx.buffer_id::<u32>(floats).unwrap_err().to_string();
    assert_eq!(
        e,
        "buffer 0: asked for a bindless id of `u32` elements, but the buffer holds `f32` (Buffer<f32> (Input))"
    );
    let e = ctx.rw_buffer_id::<f32>(floats).unwrap_err().to_string();
    assert_eq!(
        e,
        "buffer 0: asked for a writable bindless id, but programs may not write an Input buffer (Buffer<f32> (Input)); \
         ask `buffer_id` for a read-only one"
    );

    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![3]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    let rg = ctx.create_program(&read_one::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let launch_error = |ctx: &mut Context| ctx.launch_1d(0, 1).unwrap_err().to_string();
    // An id of the f32 buffer set as a `BindlessBuffer<u32>`.
    ctx.set_var(Scope::Context, "data", BindlessBuffer::<u32>::from_id(1)).unwrap();
    let e = launch_error(&mut ctx);
    assert!(e.starts_with("variable `data` of program `read_one` (tests/tests/bindless_buffers.rs:"), "{e}");
    assert!(
        e.ends_with(
            "is declared `BindlessBuffer<u32>`, but the context scope sets it to the id of buffer 0 of `f32` elements"
        ),
        "{e}"
    );
    ctx.set_var(Scope::Context, "data", BindlessBuffer::<u32>::from_id(9)).unwrap();
    let e = launch_error(&mut ctx);
    assert!(e.ends_with("but the context scope sets it to id 9, which names no buffer of this context"), "{e}");
    // The output buffer's id, of the right type: the launch runs.
    ctx.set_var(Scope::Context, "data", ctx.buffer_id::<u32>(out).unwrap()).unwrap();
    ctx.launch_1d(0, 1).unwrap();
    assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), vec![3]);

    // A writable id of an input buffer, made by hand.
    let input = ctx.create_buffer::<u32>(BufferType::Input, vec![1]);
    let rg = ctx.create_program(&write_one::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    ctx.set_var(Scope::Context, "data", RwBindlessBuffer::<u32>::from_id(input.index() + 1)).unwrap();
    let e = launch_error(&mut ctx);
    assert!(e.starts_with("variable `data` of program `write_one` (tests/tests/bindless_buffers.rs:"), "{e}");
    assert!(
        e.ends_with(
            "is declared `RwBindlessBuffer<u32>`, but the context scope sets it to the id of buffer 2, \
             an Input buffer programs may not write (use a `BindlessBuffer<u32>`)"
        ),
        "{e}"
    );
}

/// Launch index `i` writes element `i / 2` through entry `i % 2` of
/// `targets` the value read at `i` through `grid`, a 2D buffer's id.
#[rt_program(ray_generation)]
pub fn write_through_ids(#[var] targets: Buffer<RwBindlessBuffer<u32>>, #[var] grid: BindlessBuffer<u32>) {
    let i = launch_index().x;
    targets[i % 2].store(i / 2, grid[i] + 1);
}

#[test]
fn a_writable_id_of_an_input_buffer_writes_nothing_and_raises_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3]);
        let input = ctx.create_buffer::<u32>(BufferType::Input, vec![5; 3]);
        // 3 x 2, element (x, y) = x + 10 y, read row by row through the id.
        let grid = ctx.create_buffer_2d::<u32>(BufferType::Input, 3, 2).unwrap();
        ctx.write_buffer(grid, &[0u32, 1, 2, 10, 11, 12]).unwrap();
        // The second names the input buffer: no host call gives such an id.
        let targets = vec![ctx.rw_buffer_id::<u32>(out).unwrap(), RwBindlessBuffer::from_id(input.index() + 1)];
        let targets = ctx.create_buffer(BufferType::Input, targets);
        ctx.set_var(Scope::Context, "targets", targets).unwrap();
        ctx.set_var(Scope::Context, "grid", ctx.buffer_id::<u32>(grid).unwrap()).unwrap();
        let rg = ctx.create_program(&write_through_ids::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let report = ctx.launch_1d(0, 6).unwrap();
        let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
        exceptions.sort();
        assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), vec![1, 3, 12], "{}", on.name());
        assert_eq!(ctx.read_buffer::<u32>(input).unwrap(), vec![5; 3], "{}", on.name());
        let raised: Vec<(u32, u32)> = [1, 3, 5].into_iter().map(|i| (i, EXCEPTION_BUFFER_ID_INVALID)).collect();
        assert_eq!(exceptions, raised, "{}", on.name());
    }
}

/// A callable reading through the id it is given.
#[rt_program(callable)]
pub fn pick(data: BindlessBuffer<f32>, i: u32) -> f32 {
    data[i] * 10.0 + data.len() as f32
}

#[rt_program(ray_generation)]
pub fn call_with_ids(
    #[var] f: Callable<fn(BindlessBuffer<f32>, u32) -> f32>,
    #[var] data: BindlessBuffer<f32>,
    #[var] mut out: RwBuffer<f32>,
) {
    let i = launch_index().x;
    out[i] = f.call(data, i);
}

#[test]
fn an_id_passed_to_a_callable_reads_the_same_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let data = ctx.create_buffer::<f32>(BufferType::Input, vec![0.5, 1.5]);
        let out = ctx.create_buffer::<f32>(BufferType::Output, vec![-1.0; 3]);
        let p = ctx.create_program(&pick::PROGRAM);
        let f = ctx.callable_id::<fn(BindlessBuffer<f32>, u32) -> f32>(p).unwrap();
        ctx.set_var(Scope::Context, "f", f).unwrap();
        ctx.set_var(Scope::Context, "data", ctx.buffer_id::<f32>(data).unwrap()).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&call_with_ids::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let report = ctx.launch_1d(0, 3).unwrap();
        let exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
        // Index 2 is past the end: zero, and the length.
        assert_eq!(ctx.read_buffer::<f32>(out).unwrap(), vec![7.0, 17.0, 2.0], "{}", on.name());
        assert_eq!(exceptions, vec![(2, EXCEPTION_BUFFER_INDEX_OUT_OF_BOUNDS)], "{}", on.name());
    }
}
