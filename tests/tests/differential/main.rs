//! Differential tests: small ray-generation programs, each run on both
//! backends over a grid of inputs, outputs compared.
//!
//! Every program is written once, in the body of a `differential!` entry,
//! and used three ways:
//!
//! 1. as a `#[rt_program(ray_generation)]` that reads its inputs from
//!    `Buffer<T>` variables at `launch_index().x` and writes its results to
//!    an `RwBuffer<T>` variable `out` (`N` results per launch index);
//! 2. on the CPU backend (Rust, as rustc compiled it) and on the wgpu backend
//!    (the compiler's WGSL in the megakernel, on lavapipe without a GPU);
//! 3. as a plain Rust closure over the same inputs: the CPU backend's results
//!    must be bit-identical to it (plumbing: buffers, indices, launch).
//!
//! The GPU's results are compared with the CPU's: integers and bools
//! exactly; floats within a tolerance ([`Tol`]) that is exact (0 ULP) for
//! what WGSL computes correctly rounded (`+ - *`, negation, comparisons,
//! rounding functions, conversions, `abs`/`min`/`max`/`clamp`...), and the
//! WGSL specification's accuracy bound otherwise, each quoted where it is
//! used (WGSL §"Floating Point Accuracy", f32 column).
//!
//! Comparisons treat `+0.0` and `-0.0` as equal (WGSL does not promise the
//! sign of a zero) and subnormal values as zero (WGSL lets implementations
//! flush them). Inputs avoid what Rust and WGSL define differently and no
//! test asserts anything about it:
//!
//! - integer overflow in `+ - *`, negation and `abs`: Rust panics (debug)
//!   where WGSL wraps; programs use `wrapping_*` over the full range and the
//!   plain operators where the inputs cannot overflow;
//! - integer division and remainder by zero and `i32::MIN / -1`: Rust panics,
//!   WGSL returns the dividend (or 0 for `%`);
//! - shift amounts of 32 or more: Rust panics (debug), WGSL uses the amount
//!   modulo 32;
//! - NaN and infinite floats, as inputs or results (`x / 0.0`, overflowing
//!   products, `sqrt(-1)`): WGSL lets implementations assume they do not
//!   occur, so `is_nan`/`is_finite`/`is_infinite` are only tested on finite
//!   values, and NaN-to-integer casts (0 in Rust) are not tested;
//! - `usize` is 64 bits on the CPU and 32 (`u32`) in WGSL: casts through
//!   `usize` are tested with values that fit in 32 bits (a negative `i32`
//!   as `usize` as `f32` is ~1.8e19 on the CPU, ~4.3e9 in WGSL);
//! - `powf` with a negative base: WGSL's `pow` is undefined there (Rust's is
//!   defined for integral exponents); bases are positive;
//! - `sin`/`cos` outside `[-pi, pi]`: WGSL bounds their error only inside
//!   that range, so angles stay inside it; `atan2` with a zero operand:
//!   WGSL bounds it only for |x| >= 2^-126 and normal `y` (lavapipe gives
//!   3pi/4 for `atan2(0, 0)`, Rust 0);
//! - the sign of a zero: WGSL lets implementations ignore it, so `signum`
//!   (-1 for -0.0 in Rust; the compiler tests the sign bit) is not given
//!   -0.0;
//! - the order of float operations: WGSL lets implementations reassociate
//!   them and fuse them (`fma` may round the product), so expressions of
//!   several operations are compared within a few ULP ([`CHAINED`]), or an
//!   absolute bound where they cancel.
//!
//! A program is a pipeline on the wgpu backend (a megakernel link), and each
//! costs a compile on lavapipe: related checks share a program where that
//! stays readable, and each `#[test]` (in the modules below, by theme) reuses
//! one context per backend for its group of programs (switching the
//! ray-generation program between launches). `RT_DIFF_VERBOSE=1` prints each
//! program's worst float difference in ULPs.

// The programs spell things out on purpose: `a == a`, `x as f32` on an
// `f32`, `|` patterns rather than ranges, `% 2 == 0`, index loops, a swap
// through a temporary, and
// constants to the last digit are what is under test.
#![allow(
    clippy::eq_op,
    clippy::unnecessary_cast,
    clippy::cast_abs_to_unsigned,
    clippy::manual_clamp,
    clippy::manual_range_patterns,
    clippy::manual_is_multiple_of,
    clippy::needless_range_loop,
    clippy::excessive_precision,
    clippy::approx_constant,
    clippy::manual_swap
)]

use rt_runtime::*;
use rt_std::prelude::*;
use rt_std::program::ProgramDescriptor;
use rt_tests::targets::On;
use std::fmt::Debug;

// ---------------------------------------------------------------------------
// Comparing floats
// ---------------------------------------------------------------------------

/// Distance between `a` and `b` in units in the last place: how many
/// representable `f32` values lie between them (0 when equal; `+0.0` and
/// `-0.0` are equal; `u64::MAX` when exactly one is NaN).
fn ulps(a: f32, b: f32) -> u64 {
    if a == b || (a.is_nan() && b.is_nan()) {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    // Map the floats onto a line of integers ordered like the floats, with
    // -0.0 and +0.0 both at 0.
    let key = |x: f32| {
        let bits = x.to_bits();
        let magnitude = (bits & 0x7fff_ffff) as i64;
        if bits >> 31 == 1 { -magnitude } else { magnitude }
    };
    key(a).abs_diff(key(b))
}

/// How far a GPU float may be from the CPU's: within `ulps` units in the
/// last place, or within `abs` of it (for results computed with
/// cancellation, where WGSL's bound is relative to the operands, not the
/// result).
#[derive(Clone, Copy, Debug)]
pub struct Tol {
    ulps: u64,
    abs: f32,
}

/// Correctly rounded in WGSL (`+ - *`, negation, conversions, rounding
/// functions, `min`/`max`/`abs`/`clamp`, comparisons): identical results.
pub const EXACT: Tol = Tol { ulps: 0, abs: 0.0 };

/// Several correctly rounded operations in one expression: WGSL lets an
/// implementation reassociate them and fuse them where that is at least as
/// accurate (WGSL §"Reassociation and Fusion": "An implementation may
/// reassociate operations"), and lavapipe does fold constants across
/// operations (`(x + c1) + c2` as `x + (c1 + c2)`): a few ULP, for results
/// where nothing cancels.
pub const CHAINED: Tol = ulp(4);

/// Within `n` ULPs.
pub const fn ulp(n: u64) -> Tol {
    Tol { ulps: n, abs: 0.0 }
}

/// Within `n` ULPs or `abs` absolutely.
pub const fn ulp_or_abs(n: u64, abs: f32) -> Tol {
    Tol { ulps: n, abs }
}

/// Subnormals count as zero (WGSL may flush them).
fn flush(x: f32) -> f32 {
    if x.is_finite() && x.abs() < f32::MIN_POSITIVE { 0.0 } else { x }
}

fn close(gpu: f32, cpu: f32, tol: Tol) -> bool {
    let (g, c) = (flush(gpu), flush(cpu));
    ulps(g, c) <= tol.ulps || (g - c).abs() <= tol.abs
}

// ---------------------------------------------------------------------------
// Values and inputs
// ---------------------------------------------------------------------------

/// One component of a result: floats compare within a tolerance, everything
/// else exactly.
#[derive(Clone, Copy, Debug)]
pub enum Comp {
    F(f32),
    I(i64),
}

/// A type programs read and write: its components, for comparison.
pub trait Value: RtData + Send + Sync + Debug + Default {
    fn comps(&self) -> Vec<Comp>;
}

macro_rules! value {
    (float: $($t:ty),*) => {$(
        impl Value for $t {
            fn comps(&self) -> Vec<Comp> {
                let mut words = vec![0u32; <$t as RtData>::LAYOUT.words as usize];
                self.write_words(&mut words);
                words.into_iter().map(|w| Comp::F(f32::from_bits(w))).collect()
            }
        }
    )*};
    (int: $($t:ty),*) => {$(
        impl Value for $t {
            fn comps(&self) -> Vec<Comp> {
                let mut words = vec![0u32; <$t as RtData>::LAYOUT.words as usize];
                self.write_words(&mut words);
                words.into_iter().map(|w| Comp::I(w as i64)).collect()
            }
        }
    )*};
}
value!(float: f32, Vec2, Vec3, Vec4, Mat3, Mat4);
value!(int: i32, u32, bool, IVec2, IVec3, IVec4, UVec2, UVec3, UVec4);

/// A program's inputs at one launch index: a tuple with one element per
/// input buffer.
pub trait Inputs: Copy + Debug {
    /// Creates the input buffers (one per element) and sets them on
    /// program `p` under `names`.
    fn upload(rows: &[Self], ctx: &mut Context, p: ProgramId, names: &[&str]);
}

fn upload_column<T: Value>(ctx: &mut Context, p: ProgramId, name: &str, column: Vec<T>) {
    let b = ctx.create_buffer(BufferType::Input, column);
    ctx.set_var(p, name, b).unwrap();
}

impl<A: Value + Copy> Inputs for (A,) {
    fn upload(rows: &[Self], ctx: &mut Context, p: ProgramId, names: &[&str]) {
        upload_column(ctx, p, names[0], rows.iter().map(|r| r.0).collect());
    }
}

impl<A: Value + Copy, B: Value + Copy> Inputs for (A, B) {
    fn upload(rows: &[Self], ctx: &mut Context, p: ProgramId, names: &[&str]) {
        upload_column(ctx, p, names[0], rows.iter().map(|r| r.0).collect());
        upload_column(ctx, p, names[1], rows.iter().map(|r| r.1).collect());
    }
}

impl<A: Value + Copy, B: Value + Copy, C: Value + Copy> Inputs for (A, B, C) {
    fn upload(rows: &[Self], ctx: &mut Context, p: ProgramId, names: &[&str]) {
        upload_column(ctx, p, names[0], rows.iter().map(|r| r.0).collect());
        upload_column(ctx, p, names[1], rows.iter().map(|r| r.1).collect());
        upload_column(ctx, p, names[2], rows.iter().map(|r| r.2).collect());
    }
}

/// Each value alone.
fn one<A: Copy>(a: &[A]) -> Vec<(A,)> {
    a.iter().map(|&a| (a,)).collect()
}

/// Every pair (the cross product).
fn pairs<A: Copy, B: Copy>(a: &[A], b: &[B]) -> Vec<(A, B)> {
    a.iter().flat_map(|&a| b.iter().map(move |&b| (a, b))).collect()
}

/// Every pair for which `keep` holds.
fn pairs_where<A: Copy, B: Copy>(a: &[A], b: &[B], keep: impl Fn(A, B) -> bool) -> Vec<(A, B)> {
    pairs(a, b).into_iter().filter(|&(a, b)| keep(a, b)).collect()
}

/// Every triple.
fn triples<A: Copy, B: Copy, C: Copy>(a: &[A], b: &[B], c: &[C]) -> Vec<(A, B, C)> {
    pairs(a, b).into_iter().flat_map(|(a, b)| c.iter().map(move |&c| (a, b, c))).collect()
}

/// `n` values from a fixed xorshift sequence mapped by `f`: reproducible
/// "random" inputs.
fn random<T>(n: usize, seed: u32, f: impl Fn(u32) -> T) -> Vec<T> {
    let mut s = seed | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            f(s)
        })
        .collect()
}

/// A uniform float in `[lo, hi)` from 32 random bits.
fn unit(bits: u32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * ((bits >> 8) as f32 / 16777216.0)
}

// ---------------------------------------------------------------------------
// The harness
// ---------------------------------------------------------------------------

/// The payload of the one ray type the contexts declare (nothing traces it:
/// see [`keep_scene_binding`]).
#[rt_payload]
pub struct Unused {
    pub v: f32,
}

#[rt_program(miss)]
pub fn unused_miss(prd: &mut Unused) {
    prd.v = 1.0;
}

/// Workaround for a runtime bug: on the wgpu backend a megakernel in which
/// nothing calls `rt_trace` never reads the scene binding, wgpu's automatic
/// bind-group layout drops it, and the launch fails in
/// `Device::create_bind_group` ("Number of bindings in bind group
/// descriptor (4) does not match the number of bindings defined in the bind
/// group layout (3)"). Every program calls this helper, whose trace keeps
/// the binding in the layout but never runs: `idx < idx` is false, which
/// naga (and so wgpu's layout) does not fold but the driver does, so the
/// traversal code is dropped before it is compiled (on lavapipe about 0.1 s
/// per program instead of 3).
#[rt_function]
pub fn keep_scene_binding(top: Object, idx: u32) {
    if idx < idx {
        let mut prd = Unused { v: 0.0 };
        rt_trace(top, Ray::new(Vec3::ZERO, Vec3::Z, 0, 0.0, 1.0), &mut prd);
    }
}

/// One context per backend, shared by a group of programs, and the
/// mismatches found so far.
pub struct Harness {
    cpu: Context,
    /// The wgpu backend with each traversal: compute, then ray queries
    /// where the adapter has them (see `rt_tests::targets`).
    gpus: Vec<Context>,
    failures: Vec<String>,
    verbose: bool,
}

impl Harness {
    fn new() -> Harness {
        Harness {
            cpu: Harness::context(On::CPU),
            gpus: [On::COMPUTE, On::RAY_QUERY].into_iter().filter(|on| on.available()).map(Harness::context).collect(),
            failures: Vec::new(),
            verbose: std::env::var_os("RT_DIFF_VERBOSE").is_some(),
        }
    }

    /// A context on `on` for the harness's programs: depth 1, a miss
    /// program, `top` an empty geometry group.
    fn context(on: On) -> Context {
        let mut ctx = on.context();
        ctx.set_max_trace_depth(1);
        let miss = ctx.create_program(&unused_miss::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        let top = ctx.create_geometry_group(&[], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", top).unwrap();
        ctx
    }

    /// Runs `desc` over `rows` on `ctx`: `n` results per row.
    fn launch<I: Inputs, R: Value>(
        ctx: &mut Context,
        desc: &'static ProgramDescriptor,
        names: &[&str],
        rows: &[I],
        n: usize,
    ) -> Vec<R> {
        let p = ctx.create_program(desc);
        I::upload(rows, ctx, p, names);
        let out = ctx.create_buffer(BufferType::Output, vec![R::default(); rows.len() * n]);
        ctx.set_var(p, "out", out).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        let report =
            ctx.launch(0, rows.len() as u32, 1).unwrap_or_else(|e| panic!("{} on {:?}: {e}", desc.name, ctx.backend()));
        assert!(report.exceptions.is_empty(), "{} on {:?}: {:?}", desc.name, ctx.backend(), report.exceptions);
        ctx.read_buffer(out).unwrap()
    }

    /// Runs a program on both backends and compares: the CPU backend with
    /// `reference` (the same body as plain Rust) bit for bit, the GPU with
    /// the CPU within `tol`.
    fn check<I: Inputs, R: Value, const N: usize>(
        &mut self,
        desc: &'static ProgramDescriptor,
        names: &[&str],
        rows: &[I],
        reference: impl Fn(I) -> [R; N],
        tol: Tol,
    ) {
        assert!(!rows.is_empty() && rows.len() <= 4096, "{}: {} rows", desc.name, rows.len());
        let t0 = std::time::Instant::now();
        let cpu: Vec<R> = Self::launch(&mut self.cpu, desc, names, rows, N);
        let t1 = std::time::Instant::now();
        let mut worst = 0u64;
        for gpu_ctx in &mut self.gpus {
            let traversal = gpu_ctx.traversal_setting().name();
            let gpu: Vec<R> = Self::launch(gpu_ctx, desc, names, rows, N);
            let mut reported = 0;
            for (i, row) in rows.iter().enumerate() {
                let expected = reference(*row);
                for k in 0..N {
                    let (c, g) = (&cpu[i * N + k], &gpu[i * N + k]);
                    let (ec, cc, gc) = (expected[k].comps(), c.comps(), g.comps());
                    let mut cpu_ok = true;
                    let mut gpu_ok = true;
                    for ((e, c), g) in ec.iter().zip(&cc).zip(&gc) {
                        match (e, c, g) {
                            (Comp::F(e), Comp::F(c), Comp::F(g)) => {
                                cpu_ok &= e.to_bits() == c.to_bits() || (e.is_nan() && c.is_nan());
                                gpu_ok &= close(*g, *c, tol);
                                if c.is_finite() && g.is_finite() {
                                    worst = worst.max(ulps(flush(*g), flush(*c)));
                                }
                            }
                            (Comp::I(e), Comp::I(c), Comp::I(g)) => {
                                cpu_ok &= e == c;
                                gpu_ok &= c == g;
                            }
                            _ => unreachable!(),
                        }
                    }
                    if (!cpu_ok || !gpu_ok) && reported < 8 {
                        reported += 1;
                        let which = if cpu_ok { "gpu != cpu" } else { "cpu != plain Rust" };
                        self.failures.push(format!(
                            "{} ({traversal}): {which} at inputs {row:?}, result {k}: rust {:?}, cpu {c:?}, gpu {g:?} ({tol:?})",
                            desc.name, expected[k]
                        ));
                    }
                }
            }
        }
        let t2 = std::time::Instant::now();
        if self.verbose {
            eprintln!(
                "{}: {} rows x {N}, worst float difference {worst} ulp (cpu {:?}, gpu {:?})",
                desc.name,
                rows.len(),
                t1 - t0,
                t2 - t1
            );
        }
    }

    /// Runs a program on both backends and checks each result against a
    /// value written down by hand (floats bit for bit, `-0.0 == 0.0`).
    fn expect<I: Inputs, R: Value, const N: usize>(
        &mut self,
        desc: &'static ProgramDescriptor,
        names: &[&str],
        cases: &[(I, [R; N])],
    ) {
        let rows: Vec<I> = cases.iter().map(|c| c.0).collect();
        for ctx in std::iter::once(&mut self.cpu).chain(&mut self.gpus) {
            let backend = (ctx.backend(), ctx.traversal_setting());
            let got: Vec<R> = Self::launch(ctx, desc, names, &rows, N);
            for (i, (row, expected)) in cases.iter().enumerate() {
                for k in 0..N {
                    let same = expected[k].comps().iter().zip(got[i * N + k].comps()).all(|(e, g)| match (e, g) {
                        (Comp::F(e), Comp::F(g)) => e == &g || e.to_bits() == g.to_bits(),
                        (Comp::I(e), Comp::I(g)) => *e == g,
                        _ => false,
                    });
                    if !same {
                        self.failures.push(format!(
                            "{} on {backend:?} at inputs {row:?}, result {k}: expected {:?}, got {:?}",
                            desc.name,
                            expected[k],
                            got[i * N + k]
                        ));
                    }
                }
            }
        }
    }

    fn finish(self) {
        assert!(self.failures.is_empty(), "{} mismatches:\n{}", self.failures.len(), self.failures.join("\n"));
    }
}

/// The tolerance given, else [`EXACT`].
macro_rules! tol_or_exact {
    () => {
        EXACT
    };
    ($tol:expr) => {
        $tol
    };
}

/// Declares one `#[test]` and its programs. Each entry
///
/// ```text
/// /// doc
/// name(a: A, b: B) -> [R; N] over ROWS, tol TOL => { body }
/// ```
///
/// is a ray-generation program `name` with input buffers `a: Buffer<A>`,
/// `b: Buffer<B>` and output `out: RwBuffer<R>`, whose `body` computes `N`
/// results from `a` and `b`, run over `ROWS` (tuples of inputs) and
/// compared within `TOL` (default [`EXACT`]). The program's module is
/// `pub(super)`: the spot checks (`edge_cases`) launch some of them.
macro_rules! differential {
    (
        $(#[$test_meta:meta])*
        fn $test:ident {
            $(
                $(#[$meta:meta])*
                $name:ident ( $($a:ident : $ta:ident),+ ) -> [$r:ident; $n:tt]
                over $rows:expr $(, tol $tol:expr)? => $body:block
            )*
        }
    ) => {
        $(
            #[allow(non_snake_case)]
            pub(super) mod $name {
                use super::*;

                $(#[$meta])*
                #[rt_program(ray_generation)]
                pub fn $name($(#[var] $a: Buffer<$ta>,)+ #[var] mut out: RwBuffer<$r>, #[var] top: Object) {
                    let idx = launch_index().x;
                    keep_scene_binding(top, idx);
                    $(let $a = $a[idx];)+
                    let res: [$r; $n] = $body;
                    for k in 0u32..$n {
                        out[idx * $n + k] = res[k as usize];
                    }
                }

                pub fn check(h: &mut Harness) {
                    let rows = $rows;
                    let tol = tol_or_exact!($($tol)?);
                    let reference = |($($a,)+): ($($ta,)+)| -> [$r; $n] { $body };
                    h.check(&$name::PROGRAM, &[$(stringify!($a)),+], &rows, reference, tol);
                }
            }
        )*

        $(#[$test_meta])*
        #[test]
        fn $test() {
            let mut h = Harness::new();
            $($name::check(&mut h);)*
            h.finish();
        }
    };
}

// The programs and their tests, by theme (after the macros above, which
// they use).

mod aliases;
mod bool_vectors;
mod closure_args;
mod control_flow;
mod edge_cases;
mod enums;
mod generic_methods;
mod generic_structs;
mod generics;
mod glam_added;
mod glam_arrays;
mod glam_more;
mod grids;
mod int_division;
mod iterators;
mod let_patterns;
mod math;
mod methods;
mod names;
mod operators;
mod options;
mod scalars;
mod std_scalars;
mod structs_arrays;
mod traits;
mod tuple_structs;
mod tuples;
mod vectors;

use grids::*;
