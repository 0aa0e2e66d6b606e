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
//! stays readable, and each `#[test]` below reuses one context per backend
//! for its group of programs (switching the ray-generation program between
//! launches). `RT_DIFF_VERBOSE=1` prints each program's worst float
//! difference in ULPs.

// The programs spell things out on purpose: `a == a`, `x as f32` on an
// `f32`, `|` patterns rather than ranges, `% 2 == 0`, index loops, and
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
    clippy::approx_constant
)]

use rt_runtime::*;
use rt_std::prelude::*;
use rt_std::program::ProgramDescriptor;
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
    gpu: Context,
    failures: Vec<String>,
    verbose: bool,
}

impl Harness {
    fn new() -> Harness {
        let setup = |backend| {
            let mut ctx = Context::new();
            ctx.set_backend(backend);
            ctx.set_max_trace_depth(1);
            let miss = ctx.create_program(&unused_miss::PROGRAM);
            ctx.set_miss_program(0, miss).unwrap();
            let top = ctx.create_geometry_group(&[], Acceleration::default()).unwrap();
            ctx.set_var(Scope::Context, "top", top).unwrap();
            ctx
        };
        Harness {
            cpu: setup(Backend::Cpu),
            gpu: setup(Backend::Wgpu),
            failures: Vec::new(),
            verbose: std::env::var_os("RT_DIFF_VERBOSE").is_some(),
        }
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
        let gpu: Vec<R> = Self::launch(&mut self.gpu, desc, names, rows, N);
        let t2 = std::time::Instant::now();
        let mut worst = 0u64;
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
                        "{}: {which} at inputs {row:?}, result {k}: rust {:?}, cpu {c:?}, gpu {g:?} ({tol:?})",
                        desc.name, expected[k]
                    ));
                }
            }
        }
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
        for ctx in [&mut self.cpu, &mut self.gpu] {
            let backend = ctx.backend();
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
/// compared within `TOL` (default [`EXACT`]).
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
            mod $name {
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

// ---------------------------------------------------------------------------
// Input grids
// ---------------------------------------------------------------------------

/// Floats for binary operators (16, so pairs are 256): signs, zero,
/// fractions, halves, small and large magnitudes whose products and
/// quotients stay finite and normal.
const F16: [f32; 16] =
    [0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.5, -3.75, 0.1, -0.3, 7.0, 1e-3, -2.5e-4, 12345.678, -98765.43, 3.0e7];

/// Floats for unary functions (64): the above, rounding edges (halves, the
/// floats next to 0.5, values around 2^23 from where every float is an
/// integer), powers of two, wide magnitudes, and random values.
fn f64_grid() -> Vec<f32> {
    let mut v = F16.to_vec();
    v.extend([
        1.5,
        -1.5,
        3.5,
        -4.5,
        0.49999997,
        -0.49999997,
        0.50000006,
        8388607.5,
        -8388607.5,
        8388608.0,
        8388609.0,
        -8388609.0,
        16777216.0,
        2.0,
        4.0,
        1024.0,
        0.25,
        -0.125,
        1.0e-20,
        -1.0e-20,
        1.0e20,
        -1.0e20,
        3.4e37,
        -3.4e37,
        0.999,
        -0.999,
        1.001,
        99.5,
        -99.5,
        100.49,
        1e-37,
        123.456,
    ]);
    v.extend(random(16, 7, |b| unit(b, -1000.0, 1000.0)));
    assert_eq!(v.len(), 64);
    v
}

/// `n` floats spread over `[lo, hi]`: both ends, and evenly in between.
fn spread(n: usize, lo: f32, hi: f32) -> Vec<f32> {
    (0..n).map(|i| lo + (hi - lo) * i as f32 / (n - 1) as f32).collect()
}

/// `i32`s for binary operators whose results must not overflow (16).
const I16: [i32; 16] = [0, 1, -1, 2, -2, 3, -3, 7, -7, 8, -8, 100, -100, 12345, -12345, 46340];

/// `i32` edges and bit patterns (16).
const I32_EDGES: [i32; 16] = [
    0,
    1,
    -1,
    i32::MAX,
    i32::MIN,
    i32::MAX - 1,
    i32::MIN + 1,
    0x5555_5555,
    -0x5555_5555,
    1 << 30,
    -(1 << 30),
    (1 << 24) + 1,
    -(1 << 24) - 1,
    65535,
    -65536,
    -7,
];

/// `i32`s over the whole range (64): the above and random values.
fn i64_grid() -> Vec<i32> {
    let mut v = I16.to_vec();
    v.extend(I32_EDGES);
    v.extend(random(32, 11, |b| b as i32));
    assert_eq!(v.len(), 64);
    v
}

/// `u32`s for binary operators whose results must not overflow (16).
const U16: [u32; 16] = [0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 100, 255, 256, 4096, 12345, 65535];

/// `u32` edges and bit patterns (16).
const U32_EDGES: [u32; 16] = [
    0,
    1,
    u32::MAX,
    u32::MAX - 1,
    0x8000_0000,
    0x7fff_ffff,
    0x5555_5555,
    0xaaaa_aaaa,
    0xdead_beef,
    (1 << 24) + 1,
    0xff00_ff00,
    0x00ff_00ff,
    0x1234_5678,
    0x8000_0001,
    3_000_000_000,
    7,
];

/// `u32`s over the whole range (64).
fn u64_grid() -> Vec<u32> {
    let mut v = U16.to_vec();
    v.extend(U32_EDGES);
    v.extend(random(32, 13, |b| b));
    assert_eq!(v.len(), 64);
    v
}

/// Shift amounts Rust and WGSL both define: 0 to 31.
fn shifts() -> Vec<u32> {
    (0..32).collect()
}

/// `Vec3`s with components in `[-r, r]` (`n` of them, the first few
/// special: zero, axes, a negative zero, halves).
fn vec3s(n: usize, r: f32, seed: u32) -> Vec<Vec3> {
    let mut v = vec![Vec3::ZERO, Vec3::X, -Vec3::Y, vec3(-0.0, 0.5, -0.5), vec3(1.5, -2.5, 0.25)];
    let bits = random(3 * n, seed, |b| unit(b, -r, r));
    v.extend(bits.chunks(3).map(|c| vec3(c[0], c[1], c[2])));
    v.truncate(n);
    v
}

/// `Vec3`s with no zero component (divisors).
fn vec3s_nonzero(n: usize, seed: u32) -> Vec<Vec3> {
    random(3 * n, seed, |b| {
        let x = unit(b, 0.25, 8.0);
        if b & 1 == 0 { x } else { -x }
    })
    .chunks(3)
    .map(|c| vec3(c[0], c[1], c[2]))
    .collect()
}

/// Unit `Vec3`s.
fn units(n: usize, seed: u32) -> Vec<Vec3> {
    vec3s(n + 8, 1.0, seed).into_iter().filter(|v| v.length() > 0.1).map(|v| v.normalize()).take(n).collect()
}

/// `Vec4`s with components in `[-r, r]`.
fn vec4s(n: usize, r: f32, seed: u32) -> Vec<Vec4> {
    random(4 * n, seed, |b| unit(b, -r, r)).chunks(4).map(|c| vec4(c[0], c[1], c[2], c[3])).collect()
}

/// `Vec3`s whose components are taken from the unary float grid (rounding
/// edges included).
fn vec3s_from_grid() -> Vec<Vec3> {
    let g = f64_grid();
    (0..64).map(|i| vec3(g[i], g[(i + 21) % 64], g[(i + 43) % 64])).collect()
}

/// Integer vectors.
fn ivec3s(n: usize, r: i32, seed: u32) -> Vec<IVec3> {
    random(3 * n, seed, |b| (b % (2 * r as u32 + 1)).wrapping_sub(r as u32) as i32)
        .chunks(3)
        .map(|c| ivec3(c[0], c[1], c[2]))
        .collect()
}

fn uvec3s(n: usize, r: u32, seed: u32) -> Vec<UVec3> {
    random(3 * n, seed, |b| b % r.saturating_add(1)).chunks(3).map(|c| uvec3(c[0], c[1], c[2])).collect()
}

/// 3x3 and 4x4 matrices with entries in `[-4, 4]`.
fn mat3s(n: usize, seed: u32) -> Vec<Mat3> {
    let mut v = vec![Mat3::IDENTITY, Mat3::ZERO, Mat3::from_diagonal(vec3(2.0, -1.0, 0.5))];
    v.extend(random(9 * n, seed, |b| unit(b, -4.0, 4.0)).chunks(9).map(Mat3::from_cols_slice));
    v.truncate(n);
    v
}

fn mat4s(n: usize, seed: u32) -> Vec<Mat4> {
    let mut v =
        vec![Mat4::IDENTITY, Mat4::from_translation(vec3(1.0, -2.0, 3.0)), Mat4::from_scale(vec3(2.0, 0.5, -1.0))];
    v.extend(random(16 * n, seed, |b| unit(b, -4.0, 4.0)).chunks(16).map(Mat4::from_cols_slice));
    v.truncate(n);
    v
}

// ---------------------------------------------------------------------------
// Arithmetic
// ---------------------------------------------------------------------------

differential! {
    /// `+ - * / %`, unary minus, compound assignment and literal typing on
    /// every scalar type.
    fn arithmetic {
        /// `+ - *` and negation: correctly rounded in WGSL (the last result
        /// chains two operations, hence [`CHAINED`]).
        f32_add_sub_mul(a: f32, b: f32) -> [f32; 5] over pairs(&F16, &F16), tol CHAINED => {
            [a + b, a - b, a * b, -a, -(a * b) + b]
        }
        /// `/`: WGSL bounds it by 2.5 ULP for |b| in [2^-126, 2^126].
        f32_div(a: f32, b: f32) -> [f32; 2] over pairs_where(&F16, &F16, |_, b| b != 0.0), tol ulp(3) => {
            [a / b, (a + 1.0) / b]
        }
        /// `%` is Rust's exact remainder with the dividend's sign (`fmod`).
        /// WGSL's `%` is `a - b * trunc(a / b)`, a whole `b` off where
        /// `a / b` rounds up to an integer (`1.0 % 0.1`: 0.1 vs 0), so the
        /// compiler lowers `%` on floats to an exact `fmod`.
        f32_rem(a: f32, b: f32) -> [f32; 2] over pairs_where(&F16, &F16, |_, b| b != 0.0) => {
            [a % b, (a * 3.0) % -b]
        }
        /// Every compound assignment on `f32`.
        f32_compound(a: f32, b: f32) -> [f32; 4] over pairs_where(&F16, &F16, |_, b| b != 0.0), tol ulp(3) => {
            let mut acc = a;
            acc += b;
            let s1 = acc;
            acc -= 0.25;
            acc *= b;
            let s2 = acc;
            acc /= b;
            let s3 = acc;
            acc %= 2.0;
            [s1, s2, s3, acc]
        }
        /// `+ - *` and negation on `i32` (no overflow for these inputs).
        i32_add_sub_mul(a: i32, b: i32) -> [i32; 5] over pairs(&I16, &I16) => {
            [a + b, a - b, a * b, -a, a * -3 + b]
        }
        /// `wrapping_*` over the whole range, edges included.
        i32_wrapping(a: i32, b: i32) -> [i32; 3] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a.wrapping_add(b), a.wrapping_sub(b), a.wrapping_mul(b)]
        }
        /// `/` truncates towards zero and `%` takes the dividend's sign, as in
        /// Rust (not division by zero nor `i32::MIN / -1`: Rust panics).
        i32_div_rem(a: i32, b: i32) -> [i32; 2]
            over pairs_where(&i64_grid(), &[-1, 3, -7, 8, i32::MIN], |a, b| !(a == i32::MIN && b == -1)) => {
            [a / b, a % b]
        }
        /// Every compound assignment on `i32`.
        i32_compound(a: i32, b: i32) -> [i32; 5] over pairs_where(&I16, &I16, |_, b| b != 0) => {
            let mut k = a;
            k += b;
            let s1 = k;
            k -= 3;
            k *= 2;
            let s2 = k;
            k /= b;
            let s3 = k;
            k %= 5;
            [s1, s2, s3, k, -k]
        }
        /// `+ *` and a subtraction that cannot underflow on `u32`.
        u32_add_sub_mul(a: u32, b: u32) -> [u32; 3] over pairs(&U16, &U16) => {
            [a + b, a * b, a.max(b) - a.min(b)]
        }
        /// `wrapping_*` over the whole range.
        u32_wrapping(a: u32, b: u32) -> [u32; 3] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a.wrapping_add(b), a.wrapping_sub(b), a.wrapping_mul(b)]
        }
        /// Unsigned `/` and `%` over the whole range.
        u32_div_rem(a: u32, b: u32) -> [u32; 2] over pairs(&u64_grid(), &[1, 3, 10, 0x8000_0000]) => {
            [a / b, a % b]
        }
        /// Every compound assignment on `u32`.
        u32_compound(a: u32, b: u32) -> [u32; 4] over pairs_where(&U16, &U16, |_, b| b != 0) => {
            let mut w = a;
            w += b;
            w *= 2;
            let s1 = w;
            w -= b;
            w /= b;
            let s2 = w;
            w %= 7;
            [s1, s2, w, w + 1]
        }
        /// Unsuffixed literals take their type from their use: `u32` next to
        /// a `u32`, `i32` by default, `f32` for float literals.
        literal_typing(a: u32, b: i32) -> [i32; 4] over pairs(&U16, &I16) => {
            let three = 3;
            let unsigned = a * 2 + 1;
            let signed = three * b - 7;
            let float = 2.5 * 2.0;
            [unsigned as i32, signed, float as i32, (unsigned % 4) as i32 - 2]
        }
    }
}

// ---------------------------------------------------------------------------
// Comparison and logic
// ---------------------------------------------------------------------------

/// A test with a side effect: counts its calls, so a skipped call shows.
#[rt_function]
pub fn counted(calls: &mut u32, result: bool) -> bool {
    *calls += 1;
    result
}

differential! {
    /// `== != < <= > >=` on every scalar type and on vectors, `&& || !`
    /// (short-circuiting), and the eager `& | ^` on `bool`.
    fn comparison_and_logic {
        /// Float comparisons (`-0.0 == 0.0`).
        f32_compare(a: f32, b: f32) -> [bool; 6] over pairs(&F16, &F16) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Signed comparisons over the whole range.
        i32_compare(a: i32, b: i32) -> [bool; 6] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Unsigned comparisons over the whole range (`0x8000_0000 > 1`).
        u32_compare(a: u32, b: u32) -> [bool; 6] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a < b, a <= b, a > b, a >= b, a == b, a != b]
        }
        /// Boolean operators on every combination of three bools.
        bool_logic(p: bool, q: bool, r: bool) -> [bool; 10]
            over triples(&[false, true], &[false, true], &[false, true]) => {
            [p && q, p || q, !p, p & q, p | q, p ^ q, p == q, p != q, p && !q || r, !(p || q) & (r ^ p)]
        }
        /// `&&` and `||` skip their right side, also when it calls a helper
        /// with a side effect; `&` and `|` do not.
        short_circuit(a: i32, b: i32) -> [u32; 6] over pairs(&I16, &I16) => {
            let mut calls = 0u32;
            let both = a > 0 && counted(&mut calls, b > 0);
            let after_and = calls;
            let either = a > 0 || counted(&mut calls, b > 0);
            let after_or = calls;
            let eager = (a > 0) & counted(&mut calls, b < 0) | counted(&mut calls, a == b);
            [both as u32, after_and, either as u32, after_or, eager as u32, calls]
        }
        /// `==` on vectors is true when all components are, `!=` when any
        /// differs.
        vector_equality(a: i32, b: i32) -> [bool; 6]
            over pairs(&[0, 1, -1, 2, 5, -7, 8, 100], &[0, 1, -1, 2, 5, -7, 8, 100]) => {
            let u = vec3(a as f32, 1.0, b as f32);
            let v = vec3(b as f32, 1.0, a as f32);
            let iu = ivec2(a, b);
            let uu = uvec4(a as u32, 3, b as u32, 4);
            [
                u == v, u != v, u.xy() == v.xy(), iu == ivec2(b, a), iu != IVec2::ZERO,
                uu == uvec4(b as u32, 3, a as u32, 4),
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Bits and shifts
// ---------------------------------------------------------------------------

/// The PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering").
#[rt_function]
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

differential! {
    /// `& | ^ !`, shifts (arithmetic `>>` on `i32`), compound bit assignment,
    /// bit counting and hashes.
    fn bits_and_shifts {
        /// Bit operators on `u32`.
        u32_bitops(a: u32, b: u32) -> [u32; 5] over pairs(&U32_EDGES, &U32_EDGES) => {
            [a & b, a | b, a ^ b, !a, !(a & b) ^ (a | !b)]
        }
        /// Bit operators on `i32`.
        i32_bitops(a: i32, b: i32) -> [i32; 5] over pairs(&I32_EDGES, &I32_EDGES) => {
            [a & b, a | b, a ^ b, !a, !(a & b) ^ (a | !b)]
        }
        /// `u32` shifts by `u32` and `i32` amounts from 0 to 31.
        u32_shifts(a: u32, s: u32) -> [u32; 5] over pairs(&U32_EDGES[..8], &shifts()) => {
            let si = s as i32;
            [a << s, a >> s, a << si, a >> si, (a << s) >> s]
        }
        /// `i32` shifts: `>>` is arithmetic (copies the sign bit).
        i32_shifts(a: i32, s: u32) -> [i32; 5] over pairs(&I32_EDGES[..8], &shifts()) => {
            let si = s as i32;
            [a << s, a >> s, a << si, a >> si, (a << s) >> s]
        }
        /// Shifts by literals, and literals shifted.
        literal_shifts(a: u32, b: i32) -> [u32; 6] over pairs(&U32_EDGES, &I32_EDGES) => {
            [a << 3, a >> 31, (b >> 4) as u32, (b << 1u32) as u32, 1 << (a % 32), (-16 >> (a % 32)) as u32]
        }
        /// Every compound bit assignment.
        compound_bits(a: u32, b: i32) -> [u32; 4] over pairs(&U32_EDGES, &I32_EDGES) => {
            let mut w = a;
            w &= 0xffff_00f0;
            w |= 1 << 31;
            w ^= b as u32;
            w <<= 3;
            w >>= 1u32;
            w <<= (b & 7) as u32;
            let mut s = b;
            s >>= 2;
            s <<= a % 8;
            s |= -16;
            s &= !(1 << 3);
            s ^= 0x55;
            s >>= (a % 5) as i32;
            [w, s as u32, !w, (!s) as u32]
        }
        /// Bit counting on `u32`.
        u32_bit_counts(a: u32) -> [u32; 4] over one(&u64_grid()) => {
            [a.count_ones(), a.leading_zeros(), a.trailing_zeros(), a.reverse_bits()]
        }
        /// Bit counting on `i32`.
        i32_bit_counts(a: i32) -> [i32; 4] over one(&i64_grid()) => {
            [a.count_ones() as i32, a.leading_zeros() as i32, a.trailing_zeros() as i32, a.reverse_bits()]
        }
        /// `is_multiple_of` (`n.is_multiple_of(0)` is `n == 0`).
        is_multiple_of(a: u32, b: u32) -> [bool; 2] over pairs(&U16, &[0, 1, 2, 3, 7, 8, 255, 65535]) => {
            [a.is_multiple_of(b), (a * 3).is_multiple_of(b + 1)]
        }
        /// Hashes: PCG and xorshift mix multiplication, shifts and xor.
        hashes(a: u32) -> [u32; 3] over one(&u64_grid()) => {
            let mut x = a | 1;
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            [pcg_hash(a), x, pcg_hash(pcg_hash(a) ^ 0x9e37_79b9)]
        }
        /// Bit operators and shifts on integer vectors, by scalars and by
        /// vectors of either signedness.
        vector_bits(a: UVec3, b: IVec3) -> [UVec3; 6] over pairs(&uvec3s(16, u32::MAX, 3), &ivec3s(16, 1 << 30, 5)) => {
            let amounts = uvec3(1, 7, 31);
            let mut w = a & b.as_uvec3() | uvec3(1, 2, 4) ^ !a;
            w <<= 2;
            w = w >> ivec3(3, 0, 1);
            w &= 0xffff;
            w |= UVec3::X;
            let signed = (b >> 1u32) << uvec3(0, 1, 2);
            [a << amounts, a >> amounts, (b >> amounts).as_uvec3(), w, signed.as_uvec3(), (b ^ -1).as_uvec3()]
        }
    }
}

// ---------------------------------------------------------------------------
// Casts
// ---------------------------------------------------------------------------

/// Floats whose integer part fits in 32 bits, for casts through `usize`.
fn f32_in_u32_range() -> Vec<f32> {
    f64_grid().into_iter().filter(|x| x.abs() < 4.0e9).collect()
}

differential! {
    /// Every `as` cast Rust allows among `f32`, `i32`, `u32`, `usize` and
    /// `bool`.
    fn casts {
        /// `f32 as i32` truncates towards zero and saturates out of range
        /// (WGSL's `i32(x)` clamps to 2147483520, the largest float below
        /// 2^31; the compiler selects `i32::MAX` from 2^31 up).
        f32_to_i32(x: f32) -> [i32; 2] over one(&f64_grid()) => {
            [x as i32, (x * 0.5) as i32]
        }
        /// `f32 as u32` truncates and saturates (negative values give 0;
        /// WGSL's `u32(x)` tops out at 4294967040).
        f32_to_u32(x: f32) -> [u32; 2] over one(&f64_grid()) => {
            [x as u32, (-x) as u32]
        }
        /// `f32 as usize` (read back through `u32`), for values that fit.
        f32_to_usize(x: f32) -> [u32; 1] over one(&f32_in_u32_range()) => {
            [(x as usize) as u32]
        }
        /// `f32 as f32` is the identity.
        f32_to_f32(x: f32) -> [f32; 1] over one(&f64_grid()) => {
            [x as f32]
        }
        /// `i32 as f32` rounds to nearest, ties to even (2^24 + 1).
        i32_to_f32(a: i32) -> [f32; 2] over one(&i64_grid()) => {
            [a as f32, (a / 3) as f32]
        }
        /// `i32 as u32` and `u32 as i32` keep the bits; `i32 as i32`.
        i32_u32_bits(a: i32) -> [i32; 3] over one(&i64_grid()) => {
            let u = a as u32;
            [(u >> 1) as i32, u as i32, a as i32]
        }
        /// `i32 as usize` keeps the bits on the way back to 32 bits; as an
        /// array index it must be non-negative.
        i32_to_usize(a: i32) -> [u32; 2] over one(&i64_grid()) => {
            let table = [10u32, 20, 30, 40];
            [(a as usize) as u32, table[(a & 3) as usize]]
        }
        /// `u32 as f32` rounds to nearest (values above 2^24 included).
        u32_to_f32(a: u32) -> [f32; 2] over one(&u64_grid()) => {
            [a as f32, (a >> 16) as f32]
        }
        /// `u32 as u32`, `u32 as usize` and back, `u32 as i32`.
        u32_casts(a: u32) -> [u32; 3] over one(&u64_grid()) => {
            [a as u32, (a as usize) as u32, (a as i32 >> 1) as u32]
        }
        /// `usize` to every type, from values that fit in 32 bits.
        usize_casts(a: u32) -> [f32; 4] over one(&u64_grid()) => {
            let z = a as usize;
            let back = z as usize;
            [z as f32, (z as i32) as f32, (z as u32 % 1000) as f32, (back % 7) as f32]
        }
        /// `bool` to every integer type (and `bool as bool`).
        bool_casts(p: bool, a: u32) -> [u32; 4] over pairs(&[false, true], &U16) => {
            let weights = [a, a + 1];
            [p as u32 + a, (p as i32 - 1) as u32, weights[p as usize], (p as bool) as u32]
        }
    }
}

// ---------------------------------------------------------------------------
// Control flow
// ---------------------------------------------------------------------------

/// Buckets a value: an early return, then an `else if` chain as the tail.
#[rt_function]
pub fn bucket(v: f32) -> i32 {
    if v < 0.0 {
        return -1;
    }
    if v == 0.0 {
        0
    } else if v < 1.0 {
        1
    } else if v < 10.0 {
        2
    } else {
        3
    }
}

/// The first `i` in `0..n` with `i * i >= target`: a return from inside a
/// loop.
#[rt_function]
pub fn first_square_at_least(n: u32, target: u32) -> u32 {
    for i in 0..n {
        if i * i >= target {
            return i;
        }
    }
    n
}

/// Pops the lowest set bit of `mask` into `bit`; false when none is left.
#[rt_function]
pub fn pop_bit(mask: &mut u32, bit: &mut u32) -> bool {
    if *mask == 0 {
        return false;
    }
    *bit = mask.trailing_zeros();
    *mask &= *mask - 1;
    true
}

differential! {
    /// `if`/`else` statements and expressions, `else if` chains, `while`,
    /// `loop`/`break`, `for` over `a..b` and `a..=b`, `continue`, early
    /// returns, `match` on integers, blocks and shadowing.
    fn control_flow {
        /// `if` as an expression and as a statement, nested.
        if_else(x: f32) -> [f32; 3] over one(&f64_grid()) => {
            let sign = if x < 0.0 { -1.0 } else if x > 0.0 { 1.0 } else { 0.0 };
            let mut y = x;
            if y > 100.0 {
                y = 100.0;
            } else {
                if y < -100.0 {
                    y = -100.0;
                }
            }
            let z = if sign > 0.0 { if y > 50.0 { 2.0 } else { 1.0 } } else { 0.5 };
            [sign, y, z]
        }
        /// An `else if` chain with an early `return` before it, in a helper.
        else_if_chain(x: f32) -> [i32; 2] over one(&f64_grid()) => {
            [bucket(x), bucket(x * 0.01 - 0.5)]
        }
        /// `while`: Collatz steps.
        while_loop(n: u32) -> [u32; 2] over one(&(1..=64).collect::<Vec<u32>>()) => {
            let mut k = n;
            let mut steps = 0u32;
            let mut peak = k;
            while k > 1 {
                if k % 2 == 0 {
                    k /= 2;
                } else {
                    k = 3 * k + 1;
                }
                peak = peak.max(k);
                steps += 1;
            }
            [steps, peak]
        }
        /// `loop` with `break`: Newton's iteration for a square root.
        loop_break(x: f32) -> [f32; 2] over one(&spread(64, 0.5, 1000.0)), tol ulp(8) => {
            let mut r = x;
            let mut iters = 0;
            loop {
                r = 0.5 * (r + x / r);
                iters += 1;
                if iters == 30 || (r * r - x).abs() < 1e-3 * x {
                    break;
                }
            }
            [r, iters as f32]
        }
        /// `for` over `a..b`, `a..=b`, empty ranges, ranges with computed and
        /// negative bounds, and `continue`.
        for_ranges(n: i32, m: i32) -> [i32; 5]
            over pairs(&[-3, -1, 0, 1, 2, 5, 9, 16], &[-2, 0, 1, 3, 4, 7, 8, 12]) => {
            let mut a = 0;
            for i in n..m {
                a += i;
            }
            let mut b = 0;
            for i in n..=m {
                b += i * i;
            }
            let mut c = 0;
            for i in 0..n + m {
                if i % 3 == 0 {
                    continue;
                }
                c += i;
            }
            let mut d = 0;
            for i in -5..=-2 {
                d = d * 2 + i;
            }
            let mut e = 0;
            for i in 1..4 {
                for j in i..=n {
                    if j > 6 {
                        break;
                    }
                    e += i * j;
                }
            }
            [a, b, c, d, e]
        }
        /// `for` over `u32` ranges; `while` with `continue` and a condition
        /// that calls a helper mutating state.
        loops_u32(mask: u32, n: u32) -> [u32; 3] over pairs(&u64_grid()[..32], &[0, 1, 5, 8]) => {
            let mut bits_seen = 0u32;
            let mut remaining = mask;
            let mut bit = 0u32;
            while pop_bit(&mut remaining, &mut bit) {
                if bit % 4 == 1 {
                    continue;
                }
                bits_seen += bit;
            }
            let mut sum = 0u32;
            for row in 0..3u32 {
                for col in row..=n + 1 {
                    sum += row * col;
                }
            }
            [bits_seen, sum, first_square_at_least(n * 3, mask % 50)]
        }
        /// `match` on `i32`: literal arms, `|` alternatives, negative
        /// literals, `_`, a binding catch-all, as a statement and as an
        /// expression inside arithmetic.
        match_i32(a: i32) -> [i32; 3] over one(&(-20..44).collect::<Vec<i32>>()) => {
            let kind = match a {
                0 => 100,
                1 | 2 => 200,
                -1 | -2 | -3 => 300,
                7 | 11 | 13 => 400,
                _ => 500,
            };
            let mut acc = 0;
            match a % 4 {
                0 => acc += 1,
                1 | -1 => {
                    acc -= 10;
                }
                -3 => {}
                _ => acc = 7,
            }
            let scaled = 1 + match a {
                0 => 0,
                d => 1000 / d,
            };
            [kind, acc, scaled]
        }
        /// `match` on `u32` with a binding arm.
        match_u32(a: u32) -> [u32; 2] over one(&(0..64).collect::<Vec<u32>>()) => {
            let lobe = match a % 8 {
                0 => 1,
                1 | 3 | 5 => 2,
                other => other * 10,
            };
            let r = match a {
                0 | 63 => 0,
                x => x * 2,
            };
            [lobe, r]
        }
        /// Blocks as expressions and as scopes; `let` shadowing.
        blocks_and_shadowing(x: f32) -> [f32; 3] over one(&f64_grid()) => {
            let v = x;
            let v = v * 2.0;
            let w = {
                let v = v + 1.0;
                v * 3.0
            };
            let mut u = v;
            {
                let u2 = u * 0.5;
                u = u2 - 1.0;
            }
            [v, w, u]
        }
    }
}

// ---------------------------------------------------------------------------
// Float vectors
// ---------------------------------------------------------------------------

differential! {
    /// glam's `Vec2`/`Vec3`/`Vec4` methods and operators.
    fn float_vectors {
        /// Component-wise `+ - *`, negation, and scalars on either side.
        vec3_arith(a: Vec3, b: Vec3) -> [Vec3; 7]
            over pairs(&vec3s(16, 100.0, 1), &vec3s(16, 100.0, 2)), tol CHAINED => {
            [a + b, a - b, a * b, -a, a * 2.5, 0.5 * b, a + 1.0 - b * -3.0]
        }
        /// Component-wise `/` and `%` (Rust's remainder per component), by
        /// vectors and by scalars (`/`: 2.5 ULP in WGSL).
        vec3_div_rem(a: Vec3, b: Vec3) -> [Vec3; 4]
            over pairs(&vec3s(16, 100.0, 3), &vec3s_nonzero(16, 4)), tol ulp(3) => {
            [a / b, a / 4.0, 2.0 / b, a % b + a % 3.0 - 7.5 % b]
        }
        /// Compound assignment by vectors and scalars, component access by
        /// field and by index, and component assignment.
        vec3_compound(a: Vec3, b: Vec3) -> [Vec3; 4]
            over pairs(&vec3s(16, 10.0, 5), &vec3s_nonzero(16, 6)), tol ulp(3) => {
            let mut c = a;
            c += b;
            c -= Vec3::X;
            c *= b;
            let s1 = c;
            c *= 0.5;
            c /= b;
            c /= 2.0;
            let s2 = c;
            c.x = c[1] + c.y;
            c[2] = a.x - b[0];
            let mut d = Vec4::ZERO;
            d.w = c.z;
            d[1] = 3.0;
            [s1, s2, c, d.xyz() + d.w]
        }
        /// `dot` and `cross`: WGSL inherits their accuracy from the products
        /// and sums (in any order, possibly fused), so with cancellation the
        /// bound is absolute (a few ULP of the largest term, here <= 100).
        dot_cross(a: Vec3, b: Vec3) -> [Vec3; 3]
            over pairs(&vec3s(16, 10.0, 7), &vec3s(16, 10.0, 8)), tol ulp_or_abs(2, 4e-5) => {
            [
                a.cross(b), Vec3::splat(a.dot(b)),
                vec3(a.xy().dot(b.xy()), a.extend(1.0).dot(b.extend(-2.0)), b.cross(a).dot(a)),
            ]
        }
        /// Lengths and distances: WGSL inherits `length` from
        /// `sqrt(dot(x, x))` (`sqrt` from `1 / inverseSqrt`, 2 + 2.5 ULP).
        lengths(a: Vec3, b: Vec3) -> [f32; 6] over pairs(&vec3s(16, 10.0, 9), &vec3s(16, 10.0, 10)), tol ulp(8) => {
            [
                a.length(), a.length_squared(), a.distance(b), a.distance_squared(b),
                (a + Vec3::ONE * 20.0).length_recip(), a.xy().length(),
            ]
        }
        /// `normalize` (inherited from `x / length(x)`) and
        /// `normalize_or_zero`.
        normalize(a: Vec3) -> [Vec3; 3] over one(&vec3s(64, 50.0, 11)[1..]), tol ulp(8) => {
            [a.normalize(), a.normalize_or_zero(), (a * 0.0).normalize_or_zero() + a.xy().normalize().extend(1.0)]
        }
        /// `abs`, `min`, `max`, `clamp` (exact).
        abs_min_max_clamp(a: Vec3, b: Vec3) -> [Vec3; 5] over pairs(&vec3s(16, 10.0, 12), &vec3s(16, 10.0, 13)) => {
            [a.abs(), a.min(b), a.max(b), a.clamp(Vec3::splat(-1.0), Vec3::ONE), b.clamp(a.min(b), a.max(b) + 1.0)]
        }
        /// `lerp` is glam's `a * (1 - t) + b * t`, which WGSL's `mix`
        /// inherits its accuracy from; reassociated or fused, the two
        /// products can cancel, so the bound is absolute, a few ULP of
        /// |a| + |b| (here <= 200).
        lerp(a: Vec3, b: Vec3, t: f32) -> [Vec3; 2]
            over triples(&vec3s(8, 100.0, 14), &vec3s(8, 100.0, 15), &[0.0, 1.0, 0.5, 0.25, -0.5]),
            tol ulp_or_abs(4, 6e-5) => {
            [a.lerp(b, t), a.xy().lerp(b.xy(), 1.0 - t).extend(t)]
        }
        /// Rounding (exact): Rust's `round` (half away from zero), `fract`
        /// (`x - trunc(x)`), glam's `fract_gl` (`x - floor(x)`), `signum`
        /// (1 for +0.0; -0.0 is left out, see the top of the file).
        vec3_rounding(a: Vec3) -> [Vec3; 7]
            over one(&vec3s_from_grid().into_iter().map(|v| v + 0.0).collect::<Vec<_>>()) => {
            [a.floor(), a.ceil(), a.round(), a.trunc(), a.fract(), a.fract_gl(), a.signum()]
        }
        /// `powf` (positive bases), `sqrt`, `exp`, `ln`: WGSL's bounds are
        /// the scalar functions' (see `scalar_math`).
        vec3_powers(a: Vec3) -> [Vec3; 4] over one(&vec3s(64, 4.0, 16)), tol ulp_or_abs(64, 2.0f32.powi(-21)) => {
            let p = a.abs() + 0.01;
            [p.powf(1.7), p.sqrt(), a.exp(), p.ln()]
        }
        /// `sin`/`cos` inside `[-pi, pi]`: WGSL, absolute error 2^-11.
        vec3_trig(a: Vec3) -> [Vec3; 2] over one(&vec3s(64, 3.14159, 17)), tol ulp_or_abs(0, 2.0f32.powi(-11)) => {
            [a.sin(), a.cos()]
        }
        /// `mul_add` (WGSL: inherited from `a * b + c`, may be unfused, so
        /// one rounding of the product: absolute, |a * b| <= 100) and
        /// `recip` (2.5 ULP).
        vec3_mul_add_recip(a: Vec3, b: Vec3) -> [Vec3; 2]
            over pairs(&vec3s(16, 10.0, 18), &vec3s_nonzero(16, 19)), tol ulp_or_abs(3, 1e-5) => {
            [a.mul_add(b, Vec3::ONE), b.recip()]
        }
        /// `reflect` and `refract` as methods (WGSL: inherited from their
        /// formulas).
        vec3_reflect_refract(i: Vec3, n: Vec3) -> [Vec3; 3]
            over pairs(&units(16, 20), &units(16, 21)), tol ulp_or_abs(8, 1e-6) => {
            let n = if n.dot(i) > 0.0 { -n } else { n };
            [i.reflect(n), i.refract(n, 1.0 / 1.5), i.refract(n, 1.5)]
        }
        /// `extend`, `truncate` and swizzles (2 to 4 components, repeated).
        swizzles(a: Vec3) -> [Vec4; 6] over one(&vec3s(64, 10.0, 22)) => {
            let h = a.extend(1.0);
            let back = h.truncate().extend(2.0);
            let two = a.xy().extend(a.z).extend(3.0);
            let uv = a.zx() + a.yy();
            [h, back, two, a.xyzx() + a.zzzz(), h.wzyx() + h.xxyy(), vec4(uv.x, uv.y, a.yz().x, a.zyx().y)]
        }
        /// `element_sum`, `element_product`, `min_element`, `max_element` on
        /// `Vec2`, `Vec3`, `Vec4`. The compiler sums left to right; glam's
        /// SSE2 `Vec4` pairwise (`(x + y) + (z + w)`): a rounding apart.
        reductions(a: Vec4) -> [f32; 8] over one(&vec4s(64, 100.0, 23)), tol CHAINED => {
            let b = a.xyz();
            [
                a.element_sum(),
                a.element_product(),
                a.min_element(),
                a.max_element(),
                b.element_sum(),
                b.min_element(),
                a.xy().max_element(),
                a.zw().element_product(),
            ]
        }
        /// `as_ivec*`/`as_uvec*` truncate and saturate per component like
        /// `as i32`/`as u32`; `as_vec*` rounds to nearest.
        float_to_int_vectors(a: Vec3) -> [IVec3; 4] over one(&vec3s_from_grid()) => {
            [
                a.as_ivec3(), a.as_uvec3().as_ivec3(), (a * 0.5).as_ivec3(),
                a.xy().as_ivec2().extend(a.as_uvec3().z as i32),
            ]
        }
        /// `Vec2` and `Vec4` arithmetic and constants.
        vec2_vec4(a: Vec4, b: Vec4) -> [Vec4; 5]
            over pairs(&vec4s(16, 10.0, 24), &vec4s(16, 10.0, 25)), tol CHAINED => {
            let p = a.xy() * b.zw() - Vec2::X + Vec2::NEG_Y;
            [
                a + b * 2.0 - Vec4::W,
                a * b - Vec4::splat(1.5),
                p.extend(1.0).extend(0.0),
                -a.abs() + Vec4::ONE + Vec4::NEG_X,
                a.min(b).max(Vec4::ZERO) + Vec4::Y - Vec4::NEG_ONE + Vec4::NEG_Z,
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Integer vectors
// ---------------------------------------------------------------------------

differential! {
    /// `IVec*`/`UVec*` operators and methods.
    fn integer_vectors {
        /// Arithmetic on `IVec3`: `+ - *`, `/ %` (truncating), negation,
        /// scalars on either side, compound assignment.
        ivec3_arith(a: IVec3, b: IVec3) -> [IVec3; 6] over pairs(&ivec3s(16, 1000, 26), &ivec3s(16, 1000, 27)) => {
            let d = b.abs() + IVec3::ONE;
            let mut c = a;
            c += b;
            c *= 2;
            c -= IVec3::Z;
            [a + b, a - b * 3, -a * b, a / d, a % d, c]
        }
        /// `abs`, `signum`, `min`, `max`, `clamp`, `dot` and reductions on
        /// `IVec3`.
        ivec3_methods(a: IVec3, b: IVec3) -> [i32; 8] over pairs(&ivec3s(16, 1000, 28), &ivec3s(16, 1000, 29)) => {
            let lo = a.min(b);
            let hi = a.max(b);
            [
                a.abs().element_sum(),
                a.signum().dot(ivec3(1, 10, 100)),
                lo.min_element(),
                hi.max_element(),
                a.clamp(IVec3::splat(-5), IVec3::splat(5)).element_product(),
                a.dot(b),
                b.element_product() / 1000,
                (a - b).min_element(),
            ]
        }
        /// `UVec3` arithmetic, methods and conversions.
        uvec3_ops(a: UVec3, b: UVec3) -> [UVec3; 6] over pairs(&uvec3s(16, 60000, 30), &uvec3s(16, 60000, 31)) => {
            let d = b + UVec3::ONE;
            let mut c = a;
            c *= 3;
            c %= 1000;
            [
                a + b, a.max(b) - a.min(b), a * 2 + b / d, a % d, c + UVec3::Y,
                UVec3::splat(a.dot(UVec3::ONE) + b.element_sum()),
            ]
        }
        /// Conversions between vector types: `as_vec*`, `as_ivec*`,
        /// `as_uvec*` (bit-preserving between the integer types).
        int_vector_conversions(a: IVec3) -> [Vec3; 4] over one(&ivec3s(64, i32::MAX, 32)) => {
            let u = a.as_uvec3();
            [a.as_vec3(), u.as_vec3(), u.as_ivec3().as_vec3() - a.as_vec3(), (a >> 8u32).as_vec3() * 0.5]
        }
        /// Pixel-grid math on `launch_index()`-like `UVec2`s.
        uvec2_grid(a: UVec2, b: UVec2) -> [UVec2; 4] over pairs(
            &random(16, 33, |x| uvec2(x % 640, (x >> 16) % 480)),
            &random(16, 34, |x| uvec2(x % 16 + 1, (x >> 8) % 16 + 1))
        ) => {
            let tile = a / b;
            let within = a % b;
            let checker = (tile.x + tile.y) & 1;
            [tile, within, UVec2::splat(checker), (a << 1u32) ^ (b >> UVec2::splat(2)) | uvec2(1, 2) & !UVec2::ZERO]
        }
    }
}

// ---------------------------------------------------------------------------
// Scalar math
// ---------------------------------------------------------------------------

/// Positive floats from tiny to huge.
fn positives() -> Vec<f32> {
    let mut v: Vec<f32> = f64_grid().into_iter().map(f32::abs).filter(|&x| x > 0.0).collect();
    v.extend(spread(64 - v.len(), 0.5, 2.0));
    v
}

differential! {
    /// `f32` methods: roots, powers, exponentials, logarithms, trigonometry,
    /// rounding, comparisons, tests and constants.
    fn scalar_math {
        /// `sqrt`: WGSL inherits it from `1 / inverseSqrt(x)`: 2 ULP, then a
        /// 2.5 ULP division.
        sqrt(x: f32) -> [f32; 2] over one(&positives()), tol ulp(5) => {
            [x.sqrt(), (x * 0.25).sqrt()]
        }
        /// `exp` and `exp2`: WGSL, 3 + 2 * |x| ULP (|x| <= 10 here).
        exp(x: f32) -> [f32; 2] over one(&spread(64, -10.0, 10.0)), tol ulp(23) => {
            [x.exp(), x.exp2()]
        }
        /// `ln` and `log2`: WGSL, 3 ULP outside [0.5, 2], absolute error
        /// 2^-21 inside.
        logarithms(x: f32) -> [f32; 2] over one(&positives()), tol ulp_or_abs(3, 2.0f32.powi(-21)) => {
            [x.ln(), x.log2()]
        }
        /// `sin` and `cos` inside `[-pi, pi]`: WGSL, absolute error 2^-11.
        sin_cos(x: f32) -> [f32; 2] over one(&spread(64, -3.14159, 3.14159)), tol ulp_or_abs(0, 2.0f32.powi(-11)) => {
            [x.sin(), x.cos()]
        }
        /// `tan`: WGSL inherits it from `sin(x) / cos(x)`; with |x| <= 1.2,
        /// |cos| >= 0.36 and the 2^-11 errors of both give less than 5e-3.
        tan(x: f32) -> [f32; 1] over one(&spread(64, -1.2, 1.2)), tol ulp_or_abs(0, 5e-3) => {
            [x.tan()]
        }
        /// `atan`: WGSL, 4096 ULP.
        atan(x: f32) -> [f32; 1] over one(&f64_grid()), tol ulp(4096) => {
            [x.atan()]
        }
        /// `atan2`: WGSL, 4096 ULP for |x| in [2^-126, 2^126] and `y` finite
        /// and normal: not for zeros (`atan2(0, 0)` is 0 in Rust, 3pi/4 on
        /// lavapipe).
        atan2(y: f32, x: f32) -> [f32; 1] over pairs_where(&F16, &F16, |y, x| y != 0.0 && x != 0.0), tol ulp(4096) => {
            [y.atan2(x)]
        }
        /// `asin` and `acos`: WGSL, the worse of an absolute 6.8e-5 and
        /// inheritance from `atan2(x, sqrt(1 - x * x))` (4096 ULP, plus the
        /// error of `1 - x * x` where |x| is near 1).
        asin_acos(x: f32) -> [f32; 2] over one(&spread(64, -1.0, 1.0)), tol ulp_or_abs(4096, 2e-4) => {
            [x.asin(), x.acos()]
        }
        /// Hyperbolic functions: WGSL inherits them from their `exp`
        /// formulas (`(exp(x) - exp(-x)) / 2`, ...): 3 + 2 * |x| ULP of each
        /// `exp` (|x| <= 4), absolute where the difference cancels.
        hyperbolic(x: f32) -> [f32; 3] over one(&spread(64, -4.0, 4.0)), tol ulp_or_abs(16, 2e-5) => {
            [x.sinh(), x.cosh(), x.tanh()]
        }
        /// Inverse hyperbolic functions: WGSL inherits them from their `log`
        /// formulas (`log(x + sqrt(x * x + 1))`, ...): `log`'s 2^-21
        /// absolute error near 1.
        inverse_hyperbolic(x: f32) -> [f32; 3] over one(&spread(64, -0.95, 0.95)), tol ulp_or_abs(16, 2e-6) => {
            [x.asinh(), (x.abs() + 1.0 + x * x).acosh(), x.atanh()]
        }
        /// `powi` is repeated squaring on both sides (compiler-rt's
        /// `__powisf2`, the compiler's `rt_powi`): exact for n >= 0; negative
        /// powers divide (2.5 ULP).
        powi(x: f32, n: i32) -> [f32; 1]
            over pairs(&spread(16, -8.0, 8.0), &[-6, -3, -1, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12]), tol ulp(3) => {
            [x.powi(n)]
        }
        /// `powf` with positive bases: WGSL inherits `pow` from
        /// `exp2(y * log2(x))`: 3 + 2 * |y log2 x| ULP (<= 23 here) plus
        /// `log2`'s error times |y|: under 64 ULP.
        powf(x: f32, y: f32) -> [f32; 1] over pairs(&spread(16, 0.1, 10.0), &spread(16, -3.0, 3.0)), tol ulp(64) => {
            [x.powf(y)]
        }
        /// `mul_add` is fused in Rust; WGSL's `fma` is inherited from
        /// `a * b + c` (may round the product): absolute, |a * b| <= 1e4.
        mul_add(a: f32, b: f32) -> [f32; 2]
            over pairs(&spread(16, -100.0, 100.0), &spread(16, -7.0, 7.0)), tol ulp_or_abs(1, 5e-4) => {
            [a.mul_add(b, 0.3), b.mul_add(a, -a * b)]
        }
        /// `recip` is a division (2.5 ULP); `to_radians` and `to_degrees`
        /// multiply by a constant (WGSL: inherited, 1 ULP with the constant's
        /// rounding).
        recip_degrees(x: f32) -> [f32; 3] over one(&f64_grid()[2..]), tol ulp(3) => {
            [x.recip(), x.to_radians(), x.to_degrees()]
        }
        /// Rounding (exact): `floor`, `ceil`, `trunc`, Rust's `round` (half
        /// away from zero), `round_ties_even`, `fract` (`x - trunc(x)`).
        rounding(x: f32) -> [f32; 6] over one(&f64_grid()) => {
            [x.floor(), x.ceil(), x.trunc(), x.round(), x.round_ties_even(), x.fract()]
        }
        /// `abs`, `signum` (1 for +0.0; not given -0.0), `min`, `max`,
        /// `clamp`, `f32::max`-style calls (exact).
        sign_min_max(x: f32, y: f32) -> [f32; 7] over pairs(&F16.map(|x| x + 0.0), &F16) => {
            [x.abs(), x.signum(), x.min(y), x.max(y), x.clamp(-1.0, 2.0), f32::max(x, 0.0), f32::min(y, PI)]
        }
        /// `hypot` (Rust: libm's, ~1 ULP; WGSL: `length(vec2(x, y))`,
        /// inherited from `sqrt(x * x + y * y)`).
        hypot(x: f32, y: f32) -> [f32; 1] over pairs(&F16[..13], &F16[..13]), tol ulp(8) => {
            [x.hypot(y)]
        }
        /// `is_nan`, `is_finite`, `is_infinite` on finite values (WGSL may
        /// assume there are no others), and the float constants.
        tests_and_constants(x: f32) -> [f32; 4] over one(&f64_grid()), tol CHAINED => {
            let nan = x.is_nan() as u32 + 8 * (x * 0.0).is_nan() as u32;
            let flags = nan + 2 * x.is_finite() as u32 + 4 * x.is_infinite() as u32;
            let consts = TAU * FRAC_1_PI + E * LN_2 + SQRT_2 * FRAC_PI_4 + FRAC_PI_2 + core::f32::consts::FRAC_PI_3;
            let limits = f32::MAX.min(x) + f32::MIN_POSITIVE + f32::EPSILON - f32::MIN.abs().min(1.0);
            [flags as f32, consts, limits, if x < f32::INFINITY && x > f32::NEG_INFINITY { 1.0 } else { 0.0 }]
        }
    }
}

// ---------------------------------------------------------------------------
// Shading helpers
// ---------------------------------------------------------------------------

differential! {
    /// rt-std's GLSL-style helpers: `reflect`, `refract`, `faceforward`,
    /// `smoothstep`, `mix`, `step`, `saturate`.
    fn shading_helpers {
        /// `reflect` (WGSL: inherited from `i - 2 * dot(n, i) * n`).
        reflect_fn(i: Vec3, n: Vec3) -> [Vec3; 1]
            over pairs(&units(16, 40), &units(16, 41)), tol ulp_or_abs(4, 1e-6) => {
            [reflect(i, n)]
        }
        /// `refract`, total internal reflection (zero vector) included
        /// (WGSL: inherited from its formula).
        refract_fn(i: Vec3, n: Vec3, eta: f32) -> [Vec3; 1]
            over triples(&units(8, 42), &units(8, 43), &[1.0 / 1.5, 1.0, 1.5, 2.4]), tol ulp_or_abs(8, 2e-6) => {
            let n = if n.dot(i) > 0.0 { -n } else { n };
            [refract(i, n, eta)]
        }
        /// `faceforward`: `n` if `dot(nref, i) < 0`, else `-n` (exact).
        faceforward_fn(i: Vec3, n: Vec3) -> [Vec3; 2] over pairs(&units(16, 44), &units(16, 45)) => {
            [faceforward(n, i, n), faceforward(n * 2.0, -i, Vec3::Y)]
        }
        /// `smoothstep` on scalars and vectors (WGSL: inherited from
        /// `t * t * (3 - 2 * t)` with `t = clamp((x - e0) / (e1 - e0))`).
        smoothstep_fn(x: f32, e: f32) -> [f32; 3]
            over pairs(&spread(16, -1.0, 2.0), &[0.0, 0.25, -1.0, 0.9, 1.0, 0.3, -0.5, 0.1]),
            tol ulp_or_abs(8, 1e-6) => {
            let v = smoothstep(vec3(e, 0.0, -2.0), vec3(e + 1.0, 2.0, 5.0), Vec3::splat(x));
            [smoothstep(e, e + 0.5, x), v.x + v.y, v.z]
        }
        /// `mix` with a scalar and a per-component factor (WGSL: inherited
        /// from `a * (1 - t) + b * t`, the same formula, possibly fused).
        mix_fn(a: Vec3, b: Vec3, t: f32) -> [Vec3; 3]
            over triples(&vec3s(8, 10.0, 46), &vec3s(8, 10.0, 47), &[0.0, 1.0, 0.5, 0.3]), tol ulp_or_abs(2, 2e-6) => {
            [mix(a, b, t), mix(a, b, vec3(t, 1.0 - t, 0.25)), Vec3::splat(mix(a.x, b.y, t))]
        }
        /// `step` and `saturate` on scalars and vectors (exact).
        step_saturate(x: f32, e: f32) -> [f32; 6] over pairs(&F16, &[0.0, 0.5, -0.5, 1.0, 2.5, 1e-3, -0.0, 7.0]) => {
            let v = step(vec2(e, -e), Vec2::splat(x));
            let s = saturate(vec4(x, -x, x * 0.5, e));
            [step(e, x), v.x - v.y, saturate(x), saturate(x - e), s.x + s.y, s.z * s.w]
        }
    }
}

// ---------------------------------------------------------------------------
// Matrices
// ---------------------------------------------------------------------------

differential! {
    /// `Mat3`/`Mat4`: constructors, constants, products with vectors,
    /// matrices and scalars, `transpose`, `determinant`, columns.
    fn matrices {
        /// `Mat3 * Vec3` and `mul_vec3` (WGSL: sums of products in any
        /// order, possibly fused: absolute, terms <= 40).
        mat3_vec3(m: Mat3, v: Vec3) -> [Vec3; 4]
            over pairs(&mat3s(16, 50), &vec3s(16, 10.0, 51)), tol ulp_or_abs(2, 2e-5) => {
            [m * v, m.mul_vec3(v), m.transpose() * v, Mat3::from_diagonal(v) * m.col(1)]
        }
        /// `Mat3` products, sums, scalar products (exact for `+ -` and
        /// scalars; products absolute, terms <= 16).
        mat3_mat3(a: Mat3, b: Mat3) -> [Mat3; 5]
            over pairs(&mat3s(16, 52), &mat3s(16, 53)), tol ulp_or_abs(2, 1e-5) => {
            [
                a * b, a.mul_mat3(&b), a + b - Mat3::IDENTITY, a * 2.0 + 0.5 * b,
                a.transpose() * Mat3::ZERO + Mat3::from_cols(b.z_axis, a.x_axis, b.y_axis),
            ]
        }
        /// `determinant` (WGSL gives no bound; ~30 ULP of the largest
        /// product, |det| <= 400), columns by field and by `col`.
        mat3_det_cols(m: Mat3) -> [f32; 4] over one(&mat3s(64, 54)), tol ulp_or_abs(4, 1e-3) => {
            [m.determinant(), m.x_axis.y + m.col(2).z, m.transpose().y_axis.x, m.col(0).dot(m.z_axis)]
        }
        /// `Mat4 * Vec4`, `mul_vec4`, `transform_point3`,
        /// `transform_vector3` (terms <= 40).
        mat4_vec(m: Mat4, v: Vec4) -> [Vec4; 4]
            over pairs(&mat4s(16, 55), &vec4s(16, 10.0, 56)), tol ulp_or_abs(2, 3e-5) => {
            [
                m * v, m.mul_vec4(v), m.transform_point3(v.xyz()).extend(0.0),
                m.transform_vector3(v.xyz()).extend(m.w_axis.w),
            ]
        }
        /// `Mat4` products, transposes and sums.
        mat4_mat4(a: Mat4, b: Mat4) -> [Mat4; 3]
            over pairs(&mat4s(16, 57), &mat4s(16, 58)), tol ulp_or_abs(2, 2e-5) => {
            [a * b, a.mul_mat4(&b).transpose(), a * Mat4::IDENTITY + Mat4::ZERO - b * 0.5]
        }
        /// `Mat4::determinant` (no WGSL bound; |det| <= 6e3).
        mat4_det(m: Mat4) -> [f32; 2] over one(&mat4s(64, 59)), tol ulp_or_abs(4, 2e-2) => {
            [m.determinant(), m.x_axis.truncate().length_squared()]
        }
    }
}

// ---------------------------------------------------------------------------
// Structs, arrays, helpers and constants
// ---------------------------------------------------------------------------

/// One stop of a colour ramp.
#[rt_struct]
pub struct Stop {
    pub at: f32,
    pub color: Vec3,
}

/// A struct holding an array of structs and an array of scalars.
#[rt_struct]
pub struct Ramp {
    pub stops: [Stop; 3],
    pub weights: [f32; 4],
    pub count: u32,
}

/// Running mean and count of samples.
#[rt_struct]
pub struct Accum {
    pub mean: Vec3,
    pub count: u32,
}

/// A xorshift step: advances `state`, returns a float in [0, 1).
#[rt_function]
pub fn rand(state: &mut u32) -> f32 {
    let mut x = *state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *state = x;
    (x >> 8) as f32 / 16777216.0
}

/// Adds one sample to `acc`.
#[rt_function]
pub fn accumulate(acc: &mut Accum, sample: Vec3) {
    acc.count += 1;
    acc.mean += (sample - acc.mean) / acc.count as f32;
}

/// Adds `n` random grey samples, passing its references on.
#[rt_function]
pub fn accumulate_noise(acc: &mut Accum, state: &mut u32, mut n: u32) {
    while n > 0 {
        let v = rand(state);
        accumulate(acc, Vec3::splat(v));
        n -= 1;
    }
}

/// A struct in (by reference), a struct out.
#[rt_function]
pub fn scaled(acc: &Accum, by: f32) -> Accum {
    Accum { mean: acc.mean * by, count: acc.count * 2 }
}

/// A ramp lookup: loops over an array of structs in a struct.
#[rt_function]
pub fn ramp_at(ramp: &Ramp, t: f32) -> Vec3 {
    let mut color = ramp.stops[0].color;
    for i in 1..3 {
        let lo = ramp.stops[i - 1];
        let hi = ramp.stops[i];
        if t >= lo.at && t < hi.at {
            color = lo.color + (hi.color - lo.color) * ((t - lo.at) / (hi.at - lo.at));
        }
    }
    color
}

/// Number of cells per side.
#[rt_const]
pub const STRATA: u32 = 4;
/// Cells, from another constant.
#[rt_const]
pub const CELLS: u32 = STRATA * STRATA;
/// A signed offset.
#[rt_const]
pub const BIAS: i32 = -2;
/// A vector constant.
#[rt_const]
pub const TINT: Vec3 = Vec3::new(0.9, 0.5, 0.25);
/// An array constant.
#[rt_const]
pub const STOPS: [f32; 3] = [0.5, 1.0, 2.0];

differential! {
    /// Arrays, structs, `#[rt_function]` helpers with `&`/`&mut`
    /// parameters, evaluation order, and constants.
    fn structs_arrays_helpers {
        /// Array literals, `[x; N]`, indexing and assignment with loop
        /// variables, arrays copied by value.
        arrays(a: i32) -> [i32; 6] over one(&i64_grid().into_iter().filter(|&a| a != i32::MIN).collect::<Vec<_>>()) => {
            let squares = [1, 4, 9, 16];
            let mut acc = [0i32; 4];
            for i in 0..4 {
                acc[i] = (a % 100) * squares[i];
            }
            let copy = acc;
            acc[0] = 7;
            let mut total = 0;
            for i in 0..4usize {
                total += copy[i];
            }
            let idx = (a & 3) as usize;
            [acc[0], copy[0], total, squares[idx], acc[3 - idx], [a, -a % 7, 3][(a & 1) as usize]]
        }
        /// Struct literals (fields in any order), nested structs, field
        /// assignment, copies, `T::default()`.
        structs(x: f32) -> [f32; 6] over one(&spread(64, -1.0, 2.0)) => {
            let first = Stop { at: x, color: Vec3::ONE };
            let mut ramp = Ramp {
                weights: [x, 2.0, 3.0, 4.0],
                count: 1,
                stops: [first, Stop { color: vec3(x, 0.0, 1.0), at: 0.5 }, Stop { at: 1.0, color: TINT }],
            };
            ramp.stops[1].color.y = x * 2.0;
            ramp.weights[3] *= x;
            let mut copy = ramp.stops[2];
            copy.at += 1.0;
            let blank = Stop::default();
            let other = Stop { color: Vec3::default(), at: blank.at };
            [
                ramp.stops[1].color.y, ramp.weights[3], copy.at, ramp.stops[2].at, blank.at + other.color.x,
                ramp.count as f32,
            ]
        }
        /// Arrays of structs and structs of arrays through helpers taking
        /// `&T`.
        ramp_lookup(t: f32) -> [Vec3; 1] over one(&spread(64, -0.5, 1.5)), tol ulp(3) => {
            let ramp = Ramp {
                stops: [
                    Stop { at: 0.0, color: vec3(1.0, 0.0, 0.0) },
                    Stop { at: 0.4, color: vec3(0.0, 1.0, 0.0) },
                    Stop { at: 1.0, color: vec3(0.0, 0.0, 1.0) },
                ],
                weights: [0.0; 4],
                count: 3,
            };
            [ramp_at(&ramp, t)]
        }
        /// An RNG whose state is a `&mut u32`, called repeatedly.
        rng(seed: u32) -> [f32; 4] over one(&u64_grid()), tol ulp(3) => {
            let mut s = seed | 1;
            let a = rand(&mut s);
            let b = rand(&mut s);
            [a, b, rand(&mut s) + rand(&mut s) * 2.0, (s >> 16) as f32]
        }
        /// Helpers updating a `&mut` struct and passing references on;
        /// `mut` value parameters; structs returned by value.
        accumulate_helpers(seed: u32) -> [Vec3; 3] over one(&u64_grid()), tol ulp(8) => {
            let mut s = seed | 1;
            let mut acc = Accum { mean: Vec3::ZERO, count: 0 };
            for _ in 0..3 {
                let c = vec3(rand(&mut s), rand(&mut s), rand(&mut s));
                accumulate(&mut acc, c);
            }
            accumulate_noise(&mut acc, &mut s, 4);
            let half = scaled(&acc, 0.5);
            [acc.mean, half.mean, vec3(acc.count as f32, half.count as f32, rand(&mut s))]
        }
        /// Calls with side effects run once each, in Rust's order: operands
        /// left to right, struct literal fields in source order, method
        /// receivers before arguments, `match` scrutinees once.
        evaluation_order(seed: u32) -> [f32; 6] over one(&u64_grid()), tol ulp(3) => {
            let mut s = seed | 1;
            let diff = rand(&mut s) - rand(&mut s);
            let swapped = Accum { count: (rand(&mut s) * 4.0) as u32, mean: Vec3::splat(rand(&mut s)) };
            let m = rand(&mut s).max(rand(&mut s) * 0.5);
            let lobe = match (rand(&mut s) * 3.0) as u32 {
                0 => 0.25,
                k => k as f32,
            };
            let arr = [rand(&mut s), rand(&mut s) * 10.0];
            [diff, swapped.count as f32, swapped.mean.x, m, lobe, arr[0] + arr[1]]
        }
        /// `#[rt_const]` items (scalar, computed, signed, vector, array) and
        /// `const` items in a body.
        constants(a: u32) -> [f32; 5] over one(&U16), tol CHAINED => {
            const GAMMA: f32 = 1.0 / 2.2;
            const STEPS: i32 = 3;
            let cell = ((a as i32 + BIAS + STEPS).abs() as u32) % CELLS;
            let stops = STOPS;
            let exposure = stops[(cell % STRATA) as usize % 3] + STOPS[cell as usize % 3];
            [cell as f32, exposure, TINT.y * GAMMA, (STRATA * 2) as f32, TINT.dot(Vec3::ONE)]
        }
    }
}

// ---------------------------------------------------------------------------
// Integer edge cases
// ---------------------------------------------------------------------------

differential! {
    /// The integer results Rust defines at the edges of the range, which the
    /// compiler must keep: constants, `abs` and `signum`, division by -1 and
    /// by the minimum, shifts of the extremes, and `as` between signedness.
    fn integer_edges {
        /// `i32::MIN`/`MAX`, `u32::MAX` and `MIN` constants in arithmetic.
        limits(a: i32) -> [i32; 5] over one(&I16) => {
            [
                i32::MAX - a.abs(), i32::MIN + a.abs(), (u32::MAX - a.abs() as u32) as i32, u32::MIN as i32 + a,
                i32::MAX.wrapping_add(a),
            ]
        }
        /// `abs` and `signum` over the range (not `i32::MIN.abs()`, which
        /// overflows).
        abs_signum(a: i32) -> [i32; 2]
            over one(&i64_grid().into_iter().filter(|&a| a != i32::MIN).collect::<Vec<_>>()) => {
            [a.abs(), a.signum()]
        }
        /// Division and remainder at the edges: by 1, -1 (not of
        /// `i32::MIN`), `i32::MIN` and `i32::MAX`.
        div_edges(a: i32, b: i32) -> [i32; 2]
            over pairs_where(&I32_EDGES, &[1, -1, i32::MIN, i32::MAX, 2, -2], |a, b| !(a == i32::MIN && b == -1)) => {
            [a / b, a % b]
        }
        /// Shifts of the extremes (sign bit in and out).
        shift_edges(s: u32) -> [i32; 4] over one(&shifts()) => {
            [i32::MIN >> s, i32::MAX >> s, -1 << s, (u32::MAX >> s) as i32]
        }
        /// Wrapping arithmetic at the edges.
        wrap_edges(a: i32) -> [u32; 4] over one(&I32_EDGES) => {
            [
                a.wrapping_add(i32::MAX) as u32, a.wrapping_mul(-1) as u32, (a as u32).wrapping_sub(1),
                (a as u32).wrapping_mul(0x9e37_79b9),
            ]
        }
    }
}

// ---------------------------------------------------------------------------
// Spot checks against values worked out by hand
// ---------------------------------------------------------------------------

/// `%=` on buffer elements, a field of one, and a vector element, in place.
#[rt_program(ray_generation)]
pub fn rem_in_place(#[var] mut io: RwBuffer<f32>, #[var] mut iov: RwBuffer<Vec3>, #[var] top: Object) {
    let idx = launch_index().x;
    keep_scene_binding(top, idx);
    io[idx] %= 0.1;
    iov[idx].y %= 0.3;
    iov[idx] %= Vec3::new(2.0, 0.7, 0.25);
}

/// Results Rust defines and the compiler must reproduce, written down (not
/// computed): checked on both backends, they pin the CPU reference itself.
#[test]
fn spot_checks_against_known_values() {
    let mut h = Harness::new();
    // Rust's rounding flavours: `round` half away from zero, `round_ties_even`,
    // `fract` keeps the sign.
    h.expect::<(f32,), f32, 6>(
        &rounding::rounding::PROGRAM,
        &["x"],
        &[
            ((0.5,), [0.0, 1.0, 0.0, 1.0, 0.0, 0.5]),
            ((-0.5,), [-1.0, -0.0, -0.0, -1.0, -0.0, -0.5]),
            ((2.5,), [2.0, 3.0, 2.0, 3.0, 2.0, 0.5]),
            ((-2.5,), [-3.0, -2.0, -2.0, -3.0, -2.0, -0.5]),
            ((0.49999997,), [0.0, 1.0, 0.0, 0.0, 0.0, 0.49999997]),
            ((-1.25,), [-2.0, -1.0, -1.0, -1.0, -1.0, -0.25]),
            ((8388609.0,), [8388609.0, 8388609.0, 8388609.0, 8388609.0, 8388609.0, 0.0]),
        ],
    );
    // `signum` of zeros, `min`/`max`/`clamp`.
    h.expect::<(f32, f32), f32, 7>(
        &sign_min_max::sign_min_max::PROGRAM,
        &["x", "y"],
        &[
            ((0.0, 1.0), [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
            ((-0.5, 7.0), [0.5, -1.0, -0.5, 7.0, -0.5, 0.0, PI]),
            ((-3.0, -4.0), [3.0, -1.0, -4.0, -3.0, -1.0, 0.0, -4.0]),
        ],
    );
    // Float `%` is the exact remainder with the dividend's sign.
    h.expect::<(f32, f32), f32, 2>(
        &f32_rem::f32_rem::PROGRAM,
        &["a", "b"],
        &[
            ((7.5, 2.0), [1.5, 0.5]),
            ((-7.5, 2.0), [-1.5, -0.5]),
            ((1.0, 0.1), [0.09999998658895493, 0.09999995678663254]),
            ((3.0e7, 0.1), [0.05296517163515091, 0.05889551341533661]),
            ((5.0, 5.0), [0.0, 0.0]),
        ],
    );
    // Integer division truncates; `%` takes the dividend's sign.
    h.expect::<(i32, i32), i32, 2>(
        &i32_div_rem::i32_div_rem::PROGRAM,
        &["a", "b"],
        &[
            ((-7, 3), [-2, -1]),
            ((7, -7), [-1, 0]),
            ((-8, 3), [-2, -2]),
            ((i32::MIN, -7), [306783378, -2]),
            ((5, i32::MIN), [0, 5]),
        ],
    );
    // Arithmetic right shift of negative values.
    h.expect::<(i32, u32), i32, 5>(
        &i32_shifts::i32_shifts::PROGRAM,
        &["a", "s"],
        &[((-16, 2), [-64, -4, -64, -4, -16]), ((i32::MIN, 31), [0, -1, 0, -1, 0]), ((-1, 0), [-1, -1, -1, -1, -1])],
    );
    // Float to integer casts truncate and saturate.
    h.expect::<(f32,), i32, 2>(
        &f32_to_i32::f32_to_i32::PROGRAM,
        &["x"],
        &[
            ((2.9,), [2, 1]),
            ((-2.9,), [-2, -1]),
            ((3.0e9,), [i32::MAX, 1_500_000_000]),
            ((-3.0e9,), [i32::MIN, -1_500_000_000]),
            ((1.0e20,), [i32::MAX, i32::MAX]),
        ],
    );
    h.expect::<(f32,), u32, 2>(
        &f32_to_u32::f32_to_u32::PROGRAM,
        &["x"],
        &[((-1.5,), [0, 1]), ((5.0e9,), [u32::MAX, 0]), ((-5.0e9,), [0, u32::MAX]), ((4294967040.0,), [4294967040, 0])],
    );
    // Integer to float rounds to nearest, ties to even.
    h.expect::<(i32,), f32, 2>(
        &i32_to_f32::i32_to_f32::PROGRAM,
        &["a"],
        &[((16777217,), [16777216.0, 5592405.0]), ((16777219,), [16777220.0, 5592406.0]), ((-7,), [-7.0, -2.0])],
    );
    // `powi` of a negative base.
    h.expect::<(f32, i32), f32, 1>(
        &powi::powi::PROGRAM,
        &["x", "n"],
        &[((-0.5, 2), [0.25]), ((-2.0, 3), [-8.0]), ((2.0, -2), [0.25]), ((3.0, 0), [1.0])],
    );
    // Bit counts and the hash of known values.
    h.expect::<(u32,), u32, 4>(
        &u32_bit_counts::u32_bit_counts::PROGRAM,
        &["a"],
        &[((0,), [0, 32, 32, 0]), ((1,), [1, 31, 0, 0x8000_0000]), ((0xf0,), [4, 24, 4, 0x0f00_0000])],
    );
    // Collatz from 27: 111 steps, peak 9232.
    h.expect::<(u32,), u32, 2>(
        &while_loop::while_loop::PROGRAM,
        &["n"],
        &[((27,), [111, 9232]), ((1,), [0, 1]), ((6,), [8, 16])],
    );
    // `match` arms.
    h.expect::<(i32,), i32, 3>(
        &match_i32::match_i32::PROGRAM,
        &["a"],
        &[((0,), [100, 1, 1]), ((-3,), [300, 0, -332]), ((11,), [400, 7, 91]), ((-5,), [500, -10, -199])],
    );
    h.finish();

    // In-place `%=` through buffer element places.
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let mut h = Harness::new();
        let ctx = if backend == Backend::Cpu { &mut h.cpu } else { &mut h.gpu };
        let p = ctx.create_program(&rem_in_place::PROGRAM);
        let io = ctx.create_buffer(BufferType::InputOutput, vec![1.0f32, -7.5, 0.25]);
        let iov =
            ctx.create_buffer(BufferType::InputOutput, vec![vec3(5.0, 1.0, -0.3), vec3(-3.0, 0.65, 0.5), Vec3::ZERO]);
        ctx.set_var(p, "io", io).unwrap();
        ctx.set_var(p, "iov", iov).unwrap();
        ctx.set_ray_generation_program(0, p).unwrap();
        ctx.launch(0, 3, 1).unwrap();
        assert_eq!(
            ctx.read_buffer::<f32>(io).unwrap(),
            vec![0.09999998658895493, -0.09999988973140717, 0.04999999701976776],
            "{backend:?}"
        );
        let v = ctx.read_buffer::<Vec3>(iov).unwrap();
        assert_eq!(
            v,
            vec![
                vec3(1.0, 0.09999996423721313, -0.050000011920928955),
                vec3(-1.0, 0.04999995231628418, 0.0),
                Vec3::ZERO
            ],
            "{backend:?}"
        );
    }
}
