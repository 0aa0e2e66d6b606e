//! Callable programs (`#[rt_program(callable)]`, OptiX bindless callables):
//! ids held in a variable, a buffer and a struct, called from a ray
//! generation program and a helper, with exact results on every target;
//! an invalid id raises `EXCEPTION_PROGRAM_ID_INVALID` and returns zero. A
//! callable blends two callables of its own signature; one calling its own
//! program raises as an invalid id does, and two programs that may call
//! each other are a cycle, refused at launch.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

#[rt_program(callable)]
pub fn double(x: u32) -> u32 {
    x * 2
}

#[rt_program(callable)]
pub fn square(x: u32) -> u32 {
    x * x
}

#[rt_program(callable)]
pub fn scale(v: Vec3, s: f32) -> Vec3 {
    v * s
}

#[rt_struct]
pub struct Op {
    pub f: Callable<fn(u32) -> u32>,
    pub bias: u32,
}

/// Calls through an id from a helper.
#[rt_function]
pub fn apply(op: Op, x: u32) -> u32 {
    op.f.call(x) + op.bias
}

#[allow(clippy::type_complexity)]
#[rt_program(ray_generation)]
pub fn run_calls(
    #[var] first: Callable<fn(u32) -> u32>,
    #[var] ops: Buffer<Callable<fn(u32) -> u32>>,
    #[var] op: Op,
    #[var] scaler: Callable<fn(Vec3, f32) -> Vec3>,
    #[var] mut out: RwBuffer<u32>,
    #[var] mut vecs: RwBuffer<Vec3>,
    #[var] mut echoed: RwBuffer<Callable<fn(u32) -> u32>>,
) {
    let i = launch_index().x;
    // Ids are values: stored, compared.
    echoed[i] = ops[i % 3];
    if ops[i % 3] == first {
        echoed[i] = op.f;
    }
    let by_var = first.call(i);
    let by_buffer = ops[i % 3].call(i + 1);
    out[i * 3] = by_var;
    out[i * 3 + 1] = by_buffer;
    out[i * 3 + 2] = apply(op, i);
    vecs[i] = scaler.call(vec3(1.0, 2.0, 3.0), i as f32);
}

struct Outcome {
    out: Vec<u32>,
    echoed: Vec<u32>,
    vecs: Vec<Vec3>,
    exceptions: Vec<(u32, u32)>,
}

const N: u32 = 12;

fn run(on: On) -> Outcome {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let d = ctx.create_program(&double::PROGRAM);
    let s = ctx.create_program(&square::PROGRAM);
    let sc = ctx.create_program(&scale::PROGRAM);
    let d_id = ctx.callable_id::<fn(u32) -> u32>(d).unwrap();
    let s_id = ctx.callable_id::<fn(u32) -> u32>(s).unwrap();
    let sc_id = ctx.callable_id::<fn(Vec3, f32) -> Vec3>(sc).unwrap();
    // The third entry names the callable of another signature: calls through
    // it raise and return zero.
    let wrong = Callable::<fn(u32) -> u32>::from_id(sc_id.id());
    let ops = ctx.create_buffer(BufferType::Input, vec![s_id, d_id, wrong]);
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3 * N as usize]);
    let vecs = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::ZERO; N as usize]);
    let echoed = ctx.create_buffer(BufferType::Output, vec![Callable::<fn(u32) -> u32>::from_id(99); N as usize]);
    ctx.set_var(Scope::Context, "echoed", echoed).unwrap();
    ctx.set_var(Scope::Context, "first", d_id).unwrap();
    ctx.set_var(Scope::Context, "ops", ops).unwrap();
    ctx.set_var(Scope::Context, "op", Op { f: s_id, bias: 7 }).unwrap();
    ctx.set_var(Scope::Context, "scaler", sc_id).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "vecs", vecs).unwrap();
    let rg = ctx.create_program(&run_calls::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch_1d(0, N).unwrap();
    let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
    exceptions.sort();
    let echoed = ctx.read_buffer::<Callable<fn(u32) -> u32>>(echoed).unwrap().iter().map(|c| c.id()).collect();
    Outcome { out: ctx.read_buffer(out).unwrap(), echoed, vecs: ctx.read_buffer(vecs).unwrap(), exceptions }
}

#[test]
fn callables_called_through_variables_buffers_and_structs_agree_on_every_target() {
    let mut want = Vec::new();
    let mut raised = Vec::new();
    for i in 0..N {
        let by_buffer = match i % 3 {
            0 => (i + 1) * (i + 1),
            1 => (i + 1) * 2,
            _ => {
                raised.push((i, EXCEPTION_PROGRAM_ID_INVALID));
                0
            }
        };
        want.extend([i * 2, by_buffer, i * i + 7]);
    }
    // ops holds square (id 2), double (id 1, the same as `first`: replaced by `op.f`, square)
    // and scale (id 3).
    let want_echoed: Vec<u32> = (0..N).map(|i| [2, 2, 3][i as usize % 3]).collect();
    let want_vecs: Vec<Vec3> = (0..N).map(|i| vec3(1.0, 2.0, 3.0) * i as f32).collect();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let got = run(on);
        assert_eq!(got.out, want, "{}", on.name());
        assert_eq!(got.vecs, want_vecs, "{}", on.name());
        assert_eq!(got.echoed, want_echoed, "{}", on.name());
        assert_eq!(got.exceptions, raised, "{}", on.name());
    }
}

#[test]
fn a_callable_id_of_another_signature_is_refused_naming_both_programs() {
    let mut ctx = Context::new();
    let sc = ctx.create_program(&scale::PROGRAM);
    let e = ctx.callable_id::<fn(u32) -> u32>(sc).unwrap_err().to_string();
    assert!(e.starts_with("`scale` (tests/tests/callables.rs:"), "{e}");
    assert!(e.ends_with("is a callable program of signature `fn(Vec3, f32) -> Vec3`, not `fn(u32) -> u32`"), "{e}");

    ctx.set_ray_type_count(0);
    let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3]);
    let vecs = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::ZERO; 1]);
    let sc_id = ctx.callable_id::<fn(Vec3, f32) -> Vec3>(sc).unwrap();
    let ops = ctx.create_buffer(BufferType::Input, vec![Callable::<fn(u32) -> u32>::NONE]);
    ctx.set_var(Scope::Context, "first", Callable::<fn(u32) -> u32>::from_id(sc_id.id())).unwrap();
    ctx.set_var(Scope::Context, "ops", ops).unwrap();
    ctx.set_var(Scope::Context, "op", Op { f: Callable::NONE, bias: 0 }).unwrap();
    ctx.set_var(Scope::Context, "scaler", sc_id).unwrap();
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "vecs", vecs).unwrap();
    let echoed = ctx.create_buffer(BufferType::Output, vec![Callable::<fn(u32) -> u32>::NONE; 1]);
    ctx.set_var(Scope::Context, "echoed", echoed).unwrap();
    let rg = ctx.create_program(&run_calls::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let e = ctx.launch_1d(0, 1).unwrap_err().to_string();
    assert!(e.starts_with("variable `first` of program `run_calls` (tests/tests/callables.rs:"), "{e}");
    assert!(
        e.contains("is declared `Callable<fn(u32) -> u32>`, but the context scope sets it to the id of `scale` (tests/tests/callables.rs:"),
        "{e}"
    );
    assert!(e.ends_with("a callable of signature `fn(Vec3, f32) -> Vec3`"), "{e}");
}

/// Counts down through `pong`, with both ids as plain `u32`s
/// (`ids.x` is `ping`'s, `ids.y` is `pong`'s): `ping` calls `pong` calls
/// `ping`, a cycle. It ends, but WGSL cannot run it, so no backend does.
#[rt_program(callable)]
pub fn ping(x: u32, ids: UVec2) -> u32 {
    Callable::<fn(i32, UVec2) -> u32>::from_id(ids.y).call(x as i32, ids)
}

#[rt_program(callable)]
pub fn pong(x: i32, ids: UVec2) -> u32 {
    if x <= 0 { 0 } else { 1 + Callable::<fn(u32, UVec2) -> u32>::from_id(ids.x).call((x - 1) as u32, ids) }
}

#[rt_program(ray_generation)]
pub fn run_ping(#[var] ids: UVec2, #[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    out[i] = Callable::<fn(u32, UVec2) -> u32>::from_id(ids.x).call(i, ids);
}

#[test]
fn callables_calling_each_other_in_a_cycle_are_refused_at_launch_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let ping_id = ctx.create_program(&ping::PROGRAM);
        let pong_id = ctx.create_program(&pong::PROGRAM);
        let ids = UVec2::new(
            ctx.callable_id::<fn(u32, UVec2) -> u32>(ping_id).unwrap().id(),
            ctx.callable_id::<fn(i32, UVec2) -> u32>(pong_id).unwrap().id(),
        );
        let out = ctx.create_buffer::<u32>(BufferType::Output, vec![7; 4]);
        ctx.set_var(Scope::Context, "ids", ids).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&run_ping::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let e = ctx.launch_1d(0, 4).unwrap_err().to_string();
        assert_eq!(
            e,
            "callable programs call each other in a cycle, which no backend runs (WGSL has no recursion): \
             `ping` (tests/tests/callables.rs:170) calls `pong` (tests/tests/callables.rs:175) calls `ping` \
             (tests/tests/callables.rs:170)",
            "{}",
            on.name()
        );
        // The failed launch wrote nothing and left the context usable.
        assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), vec![7; 4], "{}", on.name());
    }
}

/// Ids made in a program: from a `u32` (`from_id`, its signature by the
/// turbofish or the place it goes), `NONE` and `default()`.
#[allow(clippy::type_complexity)]
#[rt_program(ray_generation)]
pub fn make_ids(#[var] base: u32, #[var] mut out: RwBuffer<u32>, #[var] mut made: RwBuffer<Callable<fn(u32) -> u32>>) {
    let i = launch_index().x;
    let f = Callable::<fn(u32) -> u32>::from_id(base + i % 3);
    let none: Callable<fn(u32) -> u32> = Callable::NONE;
    let back: Callable<fn(u32) -> u32> = Callable::from_id(base);
    let mut got = f.call(i);
    if f == Callable::<fn(u32) -> u32>::default() || f == none {
        got = 1000;
    }
    made[i] = none;
    if i % 3 == 0 {
        made[i] = f;
    } else if i % 3 == 1 {
        made[i] = back;
    }
    out[i] = got;
}

#[test]
fn ids_made_in_a_program_call_the_same_callables_on_every_target() {
    let mut want_out = Vec::new();
    let mut want_made = Vec::new();
    let mut raised = Vec::new();
    for i in 0..N {
        // base is double's id, base + 1 square's, base + 2 `make_ids`'s own (no callable).
        want_out.push(match i % 3 {
            0 => i * 2,
            1 => i * i,
            _ => {
                raised.push((i, EXCEPTION_PROGRAM_ID_INVALID));
                0
            }
        });
        want_made.push(if i % 3 == 2 { 0 } else { 1 });
    }
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let d = ctx.create_program(&double::PROGRAM);
        ctx.create_program(&square::PROGRAM);
        let rg = ctx.create_program(&make_ids::PROGRAM);
        let base = ctx.callable_id::<fn(u32) -> u32>(d).unwrap().id();
        assert_eq!(base, 1, "{}", on.name());
        let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; N as usize]);
        let made = ctx.create_buffer(BufferType::Output, vec![Callable::<fn(u32) -> u32>::from_id(99); N as usize]);
        ctx.set_var(Scope::Context, "base", base).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        ctx.set_var(Scope::Context, "made", made).unwrap();
        ctx.set_ray_generation_program(0, rg).unwrap();
        let report = ctx.launch_1d(0, N).unwrap();
        let mut exceptions: Vec<(u32, u32)> = report.exceptions.iter().map(|e| (e.launch_index.x, e.code)).collect();
        exceptions.sort();
        assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), want_out, "{}", on.name());
        let made: Vec<u32> =
            ctx.read_buffer::<Callable<fn(u32) -> u32>>(made).unwrap().iter().map(|c| c.id()).collect();
        assert_eq!(made, want_made, "{}", on.name());
        assert_eq!(exceptions, raised, "{}", on.name());
    }
}

/// Prints its argument and a vector it makes, from inside a callable.
#[rt_program(callable)]
pub fn loud_double(x: u32) -> u32 {
    rt_printf!("double {} at {}", x, vec2(x as f32, 0.5));
    x * 2
}

#[rt_program(ray_generation)]
pub fn run_loud(#[var] f: Callable<fn(u32) -> u32>, #[var] mut out: RwBuffer<u32>) {
    let i = launch_index().x;
    out[i] = f.call(i + 10);
    rt_printf!("index {} got {}", i, out[i]);
}

#[test]
fn rt_printf_inside_a_callable_prints_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let d = ctx.create_program(&loud_double::PROGRAM);
        let d_id = ctx.callable_id::<fn(u32) -> u32>(d).unwrap();
        let out = ctx.create_buffer::<u32>(BufferType::Output, vec![0; 3]);
        ctx.set_var(Scope::Context, "f", d_id).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&run_loud::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        ctx.set_print(true, None);
        let report = ctx.launch_1d(0, 3).unwrap();
        let want: Vec<(UVec2, String)> = (0..3u32)
            .flat_map(|i| {
                [
                    (UVec2::new(i, 0), format!("double {} at [{}, 0.5]", i + 10, i + 10)),
                    (UVec2::new(i, 0), format!("index {i} got {}", 2 * (i + 10))),
                ]
            })
            .collect();
        assert_eq!(report.prints, want, "{}", on.name());
        assert_eq!(ctx.read_buffer::<u32>(out).unwrap(), vec![20, 22, 24], "{}", on.name());
        // Filtered to one launch index, the callable's line goes with it.
        ctx.set_print(true, Some(UVec2::new(1, 0)));
        let report = ctx.launch_1d(0, 3).unwrap();
        assert_eq!(report.prints, want[2..4].to_vec(), "{}", on.name());
    }
}

/// A struct whose callable field's signature names a struct declared after
/// it: the struct it names is built first.
#[rt_struct]
pub struct Lit {
    pub shade: Callable<fn(Lamp) -> Vec3>,
    pub gain: f32,
}

#[rt_struct]
pub struct Lamp {
    pub color: Vec3,
}

#[rt_program(callable)]
pub fn halve(lamp: Lamp) -> Vec3 {
    lamp.color * 0.5
}

#[rt_program(ray_generation)]
pub fn run_lit(#[var] lit: Lit, #[var] mut out: RwBuffer<Vec3>) {
    let i = launch_index().x;
    out[i] = lit.shade.call(Lamp { color: Vec3::splat(i as f32) }) * lit.gain;
}

#[test]
fn a_callable_field_may_name_a_struct_declared_after_its_own() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let h = ctx.create_program(&halve::PROGRAM);
        let shade = ctx.callable_id::<fn(Lamp) -> Vec3>(h).unwrap();
        let out = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::ZERO; 3]);
        ctx.set_var(Scope::Context, "lit", Lit { shade, gain: 4.0 }).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&run_lit::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        ctx.launch_1d(0, 3).unwrap();
        let want = vec![Vec3::ZERO, Vec3::splat(2.0), Vec3::splat(4.0)];
        assert_eq!(ctx.read_buffer::<Vec3>(out).unwrap(), want, "{}", on.name());
    }
}

/// Diffuse: an albedo times the cosine.
#[rt_program(callable)]
pub fn lambert(n: Vec3, l: Vec3) -> Vec3 {
    vec3(0.8, 0.5, 0.25) * n.dot(l).max(0.0)
}

/// A mirror: white as much as the reflected light leaves along +z.
#[rt_program(callable)]
pub fn mirror(n: Vec3, l: Vec3) -> Vec3 {
    let r = 2.0 * n.dot(l) * n - l;
    Vec3::splat(r.z.max(0.0))
}

#[rt_struct]
pub struct Mix {
    pub a: Callable<fn(Vec3, Vec3) -> Vec3>,
    pub b: Callable<fn(Vec3, Vec3) -> Vec3>,
    pub w: f32,
}

/// Calls `brdf`: from the ray generation program and from a callable.
#[rt_function]
pub fn shade(brdf: Callable<fn(Vec3, Vec3) -> Vec3>, n: Vec3, l: Vec3) -> Vec3 {
    brdf.call(n, l)
}

/// Two BRDFs of its own signature mixed by `w`, one called directly, one
/// through a helper.
#[rt_program(callable)]
pub fn blend(n: Vec3, l: Vec3, #[var] mix: Mix) -> Vec3 {
    mix.a.call(n, l) * (1.0 - mix.w) + shade(mix.b, n, l) * mix.w
}

/// Every pixel shades its own normal with `brdf`, through the helper.
#[rt_program(ray_generation)]
pub fn run_brdf(#[var] brdf: Callable<fn(Vec3, Vec3) -> Vec3>, #[var] mut image: RwBuffer<Vec3>) {
    let (i, dim) = (launch_index(), launch_dim());
    let n = vec3(i.x as f32 - 1.5, i.y as f32 - 1.0, 2.0).normalize();
    image[i.y * dim.x + i.x] = shade(brdf, n, LIGHT);
}

#[rt_const]
pub const LIGHT: Vec3 = Vec3::new(0.36, 0.48, 0.8);

const W: u32 = 4;
const H: u32 = 3;

type Brdf = Callable<fn(Vec3, Vec3) -> Vec3>;

/// The image `run_brdf` makes of `blend` and the codes of its exceptions:
/// `lambert`, `mirror` and `blend` twice are created, and `mix(ids)` is
/// the second `blend`'s, the one called.
fn blend_image(on: On, mix: impl Fn(&[Brdf]) -> Mix) -> (Vec<Vec3>, Vec<u32>) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let programs = [&lambert::PROGRAM, &mirror::PROGRAM, &blend::PROGRAM, &blend::PROGRAM];
    let programs: Vec<ProgramId> = programs.into_iter().map(|p| ctx.create_program(p)).collect();
    let ids: Vec<Brdf> = programs.iter().map(|p| ctx.callable_id::<fn(Vec3, Vec3) -> Vec3>(*p).unwrap()).collect();
    ctx.set_var(programs[3], "mix", mix(&ids)).unwrap();
    ctx.set_var(Scope::Context, "mix", Mix { a: ids[0], b: ids[0], w: 0.0 }).unwrap();
    let image = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::splat(9.0); (W * H) as usize]);
    ctx.set_var(Scope::Context, "brdf", ids[3]).unwrap();
    ctx.set_var(Scope::Context, "image", image).unwrap();
    let rg = ctx.create_program(&run_brdf::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let report = ctx.launch(0, W, H).unwrap();
    (ctx.read_buffer(image).unwrap(), report.exceptions.iter().map(|e| e.code).collect())
}

/// The reference pixels: `a` and `b` mixed by `w`.
fn blended(a: fn(Vec3, Vec3) -> Vec3, b: fn(Vec3, Vec3) -> Vec3, w: f32) -> Vec<Vec3> {
    (0..W * H)
        .map(|p| {
            let n = vec3((p % W) as f32 - 1.5, (p / W) as f32 - 1.0, 2.0).normalize();
            a(n, LIGHT) * (1.0 - w) + b(n, LIGHT) * w
        })
        .collect()
}

fn black(_: Vec3, _: Vec3) -> Vec3 {
    Vec3::ZERO
}

fn assert_close(got: &[Vec3], want: &[Vec3], on: On) {
    assert_eq!(got.len(), want.len(), "{}", on.name());
    for (p, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(g.abs_diff_eq(*w, 1e-5), "{}: pixel {p}: {g} != {w}", on.name());
    }
}

#[test]
fn a_callable_blends_two_callables_of_its_own_signature_on_every_target() {
    let want = blended(lambert, mirror, 0.25);
    // Both BRDFs show in every pixel.
    assert!(want.iter().all(|c| c.x > 0.1 && c.x != c.z), "{want:?}");
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (image, exceptions) = blend_image(on, |ids| Mix { a: ids[0], b: ids[1], w: 0.25 });
        assert_close(&image, &want, on);
        assert_eq!(exceptions, Vec::<u32>::new(), "{}", on.name());
    }
}

#[test]
fn a_callable_calling_its_own_program_raises_and_gets_zero_on_every_target() {
    let raised = vec![EXCEPTION_PROGRAM_ID_INVALID; (W * H) as usize];
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        // Its own id, through the helper.
        let (image, exceptions) = blend_image(on, |ids| Mix { a: ids[0], b: ids[3], w: 0.25 });
        assert_close(&image, &blended(lambert, black, 0.25), on);
        assert_eq!(exceptions, raised, "{}", on.name());
        // The other id of the same program, directly.
        let (image, exceptions) = blend_image(on, |ids| Mix { a: ids[2], b: ids[1], w: 0.25 });
        assert_close(&image, &blended(black, mirror, 0.25), on);
        assert_eq!(exceptions, raised, "{}", on.name());
    }
}

/// Half of what `under` gives: of `blend`'s signature and calling it, so
/// with `blend` in a scene the two may call each other.
#[rt_program(callable)]
pub fn layer(n: Vec3, l: Vec3, #[var] under: Callable<fn(Vec3, Vec3) -> Vec3>) -> Vec3 {
    under.call(n, l) * 0.5
}

#[test]
fn two_callables_of_one_signature_calling_it_are_a_cycle_refused_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let mut ctx = on.context();
        ctx.set_ray_type_count(0);
        let b = ctx.create_program(&blend::PROGRAM);
        let l = ctx.create_program(&layer::PROGRAM);
        let m = ctx.create_program(&mirror::PROGRAM);
        let (b, l, m) = (
            ctx.callable_id::<fn(Vec3, Vec3) -> Vec3>(b).unwrap(),
            ctx.callable_id::<fn(Vec3, Vec3) -> Vec3>(l).unwrap(),
            ctx.callable_id::<fn(Vec3, Vec3) -> Vec3>(m).unwrap(),
        );
        // The ids set would end, but which programs may call which is
        // what the link knows: the variables change without relinking.
        ctx.set_var(Scope::Context, "mix", Mix { a: l, b: m, w: 0.5 }).unwrap();
        ctx.set_var(Scope::Context, "under", m).unwrap();
        let image = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::ZERO; 2]);
        ctx.set_var(Scope::Context, "brdf", b).unwrap();
        ctx.set_var(Scope::Context, "image", image).unwrap();
        let rg = ctx.create_program(&run_brdf::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let e = ctx.launch(0, 2, 1).unwrap_err().to_string();
        assert_eq!(
            e,
            "callable programs call each other in a cycle, which no backend runs (WGSL has no recursion): \
             `blend` (tests/tests/callables.rs:395) calls `layer` (tests/tests/callables.rs:486) calls `blend` \
             (tests/tests/callables.rs:395)",
            "{}",
            on.name()
        );
    }
}
