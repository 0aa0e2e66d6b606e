//! `#[var]` variables in callable programs, resolved as OptiX resolves a
//! bindless callable program's: the callable program's own scope, then the
//! context's. The same callable created three times with its own values,
//! or none (the context's); a buffer variable; a callable with variables
//! calling another with variables; exact on every target. A variable set
//! nowhere fails the launch naming the callable.

use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::targets::On;

/// `c` times `strength`, plus `offset`.
#[rt_program(callable)]
pub fn tint(c: Vec3, #[var] strength: f32, #[var] offset: Vec3) -> Vec3 {
    c * strength + offset
}

/// `next` of `table[i]`: both variables of this callable.
#[rt_program(callable)]
pub fn lookup(#[var] table: Buffer<u32>, i: u32, #[var] next: Callable<fn(i32) -> i32>) -> u32 {
    next.call(table[i] as i32) as u32
}

/// `x + k`.
#[rt_program(callable)]
pub fn add_k(x: i32, #[var] k: i32) -> i32 {
    x + k
}

#[allow(clippy::type_complexity)]
#[rt_program(ray_generation)]
pub fn run_tints(
    #[var] tints: Buffer<Callable<fn(Vec3) -> Vec3>>,
    #[var] look: Callable<fn(u32) -> u32>,
    #[var] mut out: RwBuffer<Vec3>,
    #[var] mut words: RwBuffer<u32>,
) {
    let i = launch_index().x;
    out[i] = tints[i % tints.len()].call(vec3(1.0, 2.0, 3.0));
    words[i] = look.call(i);
}

const N: u32 = 6;

/// The scene: three `tint`s (strength 2 and 3 in their own scopes, the
/// third the context's 10; offset the context's but for the second's own),
/// and `lookup` over its own table calling `add_k` (its own `k` = 5, the
/// context's 1000 unused). `strength`: whether the context sets it.
fn scene(on: On, strength: bool) -> (Context, BufferId, BufferId) {
    let mut ctx = on.context();
    ctx.set_ray_type_count(0);
    let t: Vec<ProgramId> = (0..3).map(|_| ctx.create_program(&tint::PROGRAM)).collect();
    ctx.set_var(t[0], "strength", 2.0f32).unwrap();
    ctx.set_var(t[1], "strength", 3.0f32).unwrap();
    ctx.set_var(t[1], "offset", Vec3::new(0.0, 1.0, 0.0)).unwrap();
    if strength {
        ctx.set_var(Scope::Context, "strength", 10.0f32).unwrap();
    }
    ctx.set_var(Scope::Context, "offset", Vec3::new(0.5, 0.0, 0.0)).unwrap();
    let ids = t.iter().map(|p| ctx.callable_id::<fn(Vec3) -> Vec3>(*p).unwrap()).collect();
    let tints = ctx.create_buffer(BufferType::Input, ids);
    ctx.set_var(Scope::Context, "tints", tints).unwrap();

    let add = ctx.create_program(&add_k::PROGRAM);
    ctx.set_var(add, "k", 5i32).unwrap();
    ctx.set_var(Scope::Context, "k", 1000i32).unwrap();
    let look = ctx.create_program(&lookup::PROGRAM);
    let table = ctx.create_buffer(BufferType::Input, vec![10u32, 20, 30, 40, 50, 60]);
    ctx.set_var(look, "table", table).unwrap();
    let next = ctx.callable_id::<fn(i32) -> i32>(add).unwrap();
    ctx.set_var(look, "next", next).unwrap();
    let look_id = ctx.callable_id::<fn(u32) -> u32>(look).unwrap();
    ctx.set_var(Scope::Context, "look", look_id).unwrap();

    let out = ctx.create_buffer::<Vec3>(BufferType::Output, vec![Vec3::ZERO; N as usize]);
    let words = ctx.create_buffer::<u32>(BufferType::Output, vec![0; N as usize]);
    ctx.set_var(Scope::Context, "out", out).unwrap();
    ctx.set_var(Scope::Context, "words", words).unwrap();
    let rg = ctx.create_program(&run_tints::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    (ctx, out, words)
}

#[test]
fn callables_read_their_own_variables_then_the_contexts_on_every_target() {
    let tinted = [Vec3::new(2.5, 4.0, 6.0), Vec3::new(3.0, 7.0, 9.0), Vec3::new(10.5, 20.0, 30.0)];
    let want_out: Vec<Vec3> = (0..N).map(|i| tinted[i as usize % 3]).collect();
    let want_words: Vec<u32> = (0..N).map(|i| 10 * (i + 1) + 5).collect();
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (mut ctx, out, words) = scene(on, true);
        let report = ctx.launch_1d(0, N).unwrap();
        assert!(report.exceptions.is_empty(), "{}: {:?}", on.name(), report.exceptions);
        assert_eq!(ctx.read_buffer::<Vec3>(out).unwrap(), want_out, "{}", on.name());
        assert_eq!(ctx.read_buffer::<u32>(words).unwrap(), want_words, "{}", on.name());
        // A new value reaches the next launch: the third tint's strength.
        ctx.set_var(Scope::Context, "strength", 20.0f32).unwrap();
        ctx.launch_1d(0, N).unwrap();
        let got = ctx.read_buffer::<Vec3>(out).unwrap();
        assert_eq!(got[2], Vec3::new(20.5, 40.0, 60.0), "{}", on.name());
        assert_eq!(got[..2], want_out[..2], "{}", on.name());
    }
}

#[test]
fn a_callables_variable_set_nowhere_fails_the_launch_naming_it_on_every_target() {
    for on in On::ALL.into_iter().filter(|on| on.available()) {
        let (mut ctx, _, _) = scene(on, false);
        let e = ctx.launch_1d(0, N).unwrap_err().to_string();
        assert!(
            e.contains("`strength`") && e.contains("`tint`") && e.contains("callable_variables.rs"),
            "{}: {e}",
            on.name()
        );
    }
}
