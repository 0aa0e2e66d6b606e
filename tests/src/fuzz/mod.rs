//! A differential fuzzer for the compiler: random programs of the subset,
//! run as Rust semantics on the CPU and as the compiler's WGSL on wgpu,
//! results compared.
//!
//! ## Design
//! 1. [`generate`] builds a random, well-typed program from a seed as an AST
//!    ([`ast`]): scalars, glam vectors, a struct or two, arithmetic, bit
//!    operations, comparisons (now and then with a `f32::NAN` operand),
//!    casts, vector methods (the dividing ones with any divisor, in method
//!    and path form), bool vectors (`cmp*` masks, `!`, `& | ^`, consumed by
//!    `any`/`all`/`bitmask`/`VecN::select`) and rt-std's math,
//!    nested `if`/`match`/loops, helpers (one taking `&mut u32`), buffer
//!    loads and stores, tuple literals read by `.0`/`.1`, and integers
//!    through an `#[rt_enum]` every program declares (`FuzzKind`, matched
//!    exhaustively), a generic helper every program declares
//!    (`fuzz_pick<T>`) called at the types of its arguments (scalars,
//!    vectors, structs); helpers whose first parameter is the last struct are
//!    often printed as its `#[rt_impl]` methods (`self`, `&self` or `&mut
//!    self`), called as `x.name(..)` or `Struct::name(x, ..)`, some of them
//!    in its impl of an `#[rt_trait] FuzzOps` the program declares, and
//!    helpers taking the struct and a right operand as its operator impls
//!    (`Add`, `Sub`, `Mul`, `Mul<f32>`), called as `(a + b)` or by name,
//!    `a.add(b)` (see `ast::Method`); closures bound and called or given to a
//!    generic helper (`fuzz_apply`), `Option`
//!    flows (`unwrap_or`, `match`, `if let`, `filter`), iterator folds and
//!    sums over array literals (`.rev()` too), each printed as the
//!    construct and interpreted as the core expression it means
//!    (`ast::Sugar`); and labelled loops left by a `break` from a loop
//!    inside them. The AST prints as the Rust source of an
//!    `#[rt_program(ray_generation)]` with its `#[rt_struct]`s and
//!    `#[rt_function]`s.
//! 2. The CPU side is [`interp`], an interpreter of that AST with Rust's
//!    semantics, run for each of [`gpu::LANES`] launch indices with inputs
//!    of its own. It *interprets* rather than compiling the printed Rust:
//!    a rustc invocation per program costs seconds (the macros, rt-std and
//!    glam, a link), which for hundreds of programs per test run is far
//!    beyond the budget, while interpreting one launch index takes
//!    microseconds. The interpreter also knows, per value, how far a
//!    conforming GPU may be from it (WGSL's accuracy rules), which compiled
//!    Rust could not tell. (The printed Rust is still real Rust: every
//!    minimized regression is added to the snapshot corpus, which rustc
//!    compiles through the real macros.)
//! 3. The GPU side lowers the printed source with
//!    [`rt_compiler::lower_source`] and runs the module's types, functions
//!    and program (not the stub prelude) on wgpu through a small harness of
//!    its own ([`gpu`]), not the runtime: a prelude defining the runtime
//!    items programs name, and a compute entry point that loads each launch
//!    index's `#[var]` inputs from the heap and calls the program with
//!    `RtBuffer`s over its output slices. Programs are batched (default 25
//!    per module, a `switch` on the workgroup) to amortise lavapipe's shader
//!    compile.
//! 4. Outputs are compared word by word: integers and bools exactly, floats
//!    within the interpreter's error bound plus 2 ULP. What is skipped, and
//!    why, is documented in [`interp`] (non-finite floats, control flow on
//!    values within rounding of a decision); skips are counted and
//!    reported.
//!
//! A failure is reported with the program's source, its WGSL, the inputs
//! and the differing words; [`Config::artifacts`] keeps them on disk, and
//! with `RT_FUZZ_MINIMIZE=<seconds>` [`reduce`] shrinks each failing
//! program (deleting statements, flattening blocks, replacing expressions
//! by operands while it still fails the same way) into `minimized.rs`.
//! `RT_FUZZ_SEED`, `RT_FUZZ_PROGRAMS`, `RT_FUZZ_BATCH` and `RT_FUZZ_ONLY`
//! (one program id) choose what a run does (see [`Config::from_env`]);
//! `RT_FUZZ_TRACE=<launch index>` prints the interpreter's values,
//! `RT_FUZZ_LANE` the differences of one launch index, `RT_FUZZ_SOURCE` runs
//! an edited source on the GPU against the generated program.
//!
//! 5. The CPU backend runs the same programs through the real macros:
//!    `build.rs` writes the fixed seed's programs as their lane-wise
//!    variant ([`generate::lanes_variant`]: traces and early returns put
//!    into their blocks, [`ast::Program::lanes_source`]: each input in a
//!    buffer of one value per launch index), and `tests/fuzz_lanes.rs`
//!    runs each one launch index at a time and lane-wise, comparing the
//!    two exactly and both with the interpreter ([`interpreted`]).
//!
//! The interpreter itself is checked against rustc by [`native`] (an
//! ignored test: it builds the generated programs natively and compares).
//! Every bug the fuzzer found has a minimized program in the snapshot
//! corpus (`snapshots/in/fuzz_regressions.rs`), run on both sides by a
//! test of its own.

// `max(0).min(1)` is deliberate where NaN must become 0 (WGSL `saturate`);
// the other lints are about the generator's and interpreter's shape.
#![allow(clippy::manual_clamp, clippy::redundant_guards, clippy::needless_range_loop, clippy::only_used_in_recursion)]

pub mod ast;
pub mod generate;
pub mod gpu;
pub mod interp;
pub mod native;
pub mod reduce;

use interp::{Stop, V, Word};
use std::fmt::Write;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What a fuzzing run does.
#[derive(Clone, Debug)]
pub struct Config {
    pub seed: u64,
    /// Program ids `first..first + programs`.
    pub first: usize,
    pub programs: usize,
    /// Programs per shader module.
    pub batch: usize,
    /// Where to write the source, WGSL and report of each failure.
    pub artifacts: Option<PathBuf>,
    /// Seconds to spend reducing each failing program (0: none); the
    /// reduced source is written as `minimized.rs` beside the artifacts.
    pub minimize_secs: u64,
}

impl Config {
    /// The defaults, overridden by `RT_FUZZ_SEED`, `RT_FUZZ_PROGRAMS`,
    /// `RT_FUZZ_BATCH`, `RT_FUZZ_ONLY=<id>` (that program alone) and
    /// `RT_FUZZ_MINIMIZE=<seconds>` (reduce each failure).
    pub fn from_env(seed: u64, programs: usize) -> Config {
        let var = |n: &str| std::env::var(n).ok().and_then(|v| v.parse::<u64>().ok());
        let mut c = Config {
            seed: var("RT_FUZZ_SEED").unwrap_or(seed),
            first: 0,
            programs: var("RT_FUZZ_PROGRAMS").map_or(programs, |v| v as usize),
            batch: var("RT_FUZZ_BATCH").map_or(25, |v| v.max(1) as usize),
            artifacts: None,
            minimize_secs: var("RT_FUZZ_MINIMIZE").unwrap_or(0),
        };
        if let Some(id) = var("RT_FUZZ_ONLY") {
            c.first = id as usize;
            c.programs = 1;
        }
        c
    }
}

/// Counts of what a run compared and skipped.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    pub programs: usize,
    pub lanes: usize,
    pub lanes_non_finite: usize,
    pub lanes_diverged: usize,
    pub words_compared: usize,
    pub words_skipped: usize,
    pub batches: usize,
    pub time_generate_lower: Duration,
    pub time_interpret: Duration,
    pub time_gpu: Duration,
}

/// A program on which the two sides disagree (or the compiler failed).
#[derive(Clone, Debug)]
pub struct Failure {
    pub id: usize,
    /// The program's name (`fuzz<id>`, or a reducer candidate's).
    pub program: String,
    /// `"rejected"` (the compiler refused the program), `"wgpu"` (its
    /// module failed on the device) or `"mismatch"`.
    pub kind: &'static str,
    pub detail: String,
    pub source: String,
    pub wgsl: String,
}

#[derive(Debug)]
pub struct Report {
    pub device: String,
    pub stats: Stats,
    pub failures: Vec<Failure>,
}

impl Report {
    /// A one-paragraph summary.
    pub fn summary(&self) -> String {
        let s = &self.stats;
        let compared = s.lanes - s.lanes_non_finite - s.lanes_diverged;
        format!(
            "{} programs in {} batches on {}: {} launch indices, {} compared ({} skipped: {} non-finite, {} diverging), \
             {} words compared, {} uncertain words skipped; {} failures. Time: generate+lower {:.1?}, interpret {:.1?}, gpu {:.1?}",
            s.programs,
            s.batches,
            self.device,
            s.lanes,
            compared,
            s.lanes_non_finite + s.lanes_diverged,
            s.lanes_non_finite,
            s.lanes_diverged,
            s.words_compared,
            s.words_skipped,
            self.failures.len(),
            s.time_generate_lower,
            s.time_interpret,
            s.time_gpu
        )
    }
}

/// One program ready to run: its AST, lowered module, inputs per launch
/// index and the interpreter's outputs per launch index.
pub struct Prepared {
    pub id: usize,
    pub program: ast::Program,
    pub source: String,
    pub lowered: rt_compiler::Lowered,
    pub inputs: Vec<Vec<V>>,
    pub expected: Vec<Result<Vec<Vec<Word>>, Stop>>,
}

/// Generates, lowers and interprets program `id`; `Err` if the compiler
/// rejects it.
pub fn prepare(seed: u64, id: usize) -> Result<Prepared, Failure> {
    let program = generate::program(seed, id);
    prepare_program(seed, id, program)
}

/// [`prepare`] for a given program (the minimizer's candidates).
pub fn prepare_program(seed: u64, id: usize, program: ast::Program) -> Result<Prepared, Failure> {
    Ok(interpret(seed, lower(id, program)?))
}

/// Lowers the program's source (no inputs or results yet). For debugging,
/// `RT_FUZZ_SOURCE=<file>` lowers that file's program of the same name
/// instead (the interpreter still runs the generated one).
fn lower(id: usize, program: ast::Program) -> Result<Prepared, Failure> {
    let source = match std::env::var("RT_FUZZ_SOURCE") {
        Ok(path) => std::fs::read_to_string(path).expect("RT_FUZZ_SOURCE"),
        Err(_) => program.source(),
    };
    let lowered = rt_compiler::lower_source(&source, &program.name).map_err(|e| Failure {
        id,
        program: program.name.clone(),
        kind: "rejected",
        detail: format!("the compiler rejects the program:\n{}", located(&e, &source)),
        source: source.clone(),
        wgsl: String::new(),
    })?;
    Ok(Prepared { id, program, source, lowered, inputs: Vec::new(), expected: Vec::new() })
}

/// Program `id` of `seed` as given (the lane-wise variant,
/// `generate::lanes_variant`), with the inputs of each launch index and
/// the interpreter's outputs, not lowered (`lowered` is empty).
pub fn interpreted(seed: u64, id: usize, program: ast::Program) -> Prepared {
    let source = program.lanes_source();
    let lowered = rt_compiler::Lowered::default();
    interpret(seed, Prepared { id, program, source, lowered, inputs: Vec::new(), expected: Vec::new() })
}

/// Draws the inputs of each launch index and runs the interpreter.
fn interpret(seed: u64, mut p: Prepared) -> Prepared {
    let mut r = generate::Rng::new(generate::program_seed(seed, p.id) ^ 0x5eed_1234_abcd_0001);
    p.inputs = (0..gpu::LANES)
        .map(|_| p.program.inputs.iter().map(|(_, t)| generate::input_value(&mut r, &p.program, t)).collect())
        .collect();
    let run = || p.inputs.iter().enumerate().map(|(lane, ins)| interp::run(&p.program, lane as u32, ins)).collect();
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(run)) {
        Ok(e) => p.expected = e,
        Err(e) => {
            let msg = e.downcast_ref::<String>().cloned().or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()));
            panic!("interpreting program {} of seed {seed}: {}\n{}", p.id, msg.unwrap_or_default(), p.source);
        }
    }
    p
}

/// Runs `f` on a thread with a large stack: generation and interpretation
/// recurse.
pub fn on_big_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .name("rt-fuzz".into())
        .stack_size(256 << 20)
        .spawn(f)
        .unwrap()
        .join()
        .unwrap_or_else(|e| std::panic::resume_unwind(e))
}

/// Runs programs `first..first + n` in batches; see the module docs.
pub fn run(cfg: &Config) -> Report {
    let cfg = cfg.clone();
    on_big_stack(move || run_here(&cfg))
}

fn run_here(cfg: &Config) -> Report {
    let gpu = gpu::Gpu::new().unwrap_or_else(|e| panic!("the fuzzer needs a wgpu adapter: {e}"));
    let mut report = Report { device: gpu.name.clone(), stats: Stats::default(), failures: Vec::new() };
    let ids: Vec<usize> = (cfg.first..cfg.first + cfg.programs).collect();
    for chunk in ids.chunks(cfg.batch) {
        let t0 = Instant::now();
        let mut batch = Vec::new();
        for &id in chunk {
            match lower(id, generate::program(cfg.seed, id)) {
                Ok(p) => batch.push(p),
                Err(f) => report.failures.push(f),
            }
        }
        report.stats.time_generate_lower += t0.elapsed();
        let t1 = Instant::now();
        let batch: Vec<Prepared> = batch.into_iter().map(|p| interpret(cfg.seed, p)).collect();
        report.stats.time_interpret += t1.elapsed();
        let t2 = Instant::now();
        if std::env::var_os("RT_FUZZ_VERBOSE").is_some() {
            eprintln!("batch of programs {}..={}", chunk[0], chunk[chunk.len() - 1]);
        }
        run_batch(&gpu, &batch, &mut report);
        report.stats.time_gpu += t2.elapsed();
        report.stats.programs += chunk.len();
        report.stats.batches += 1;
    }
    if let Some(dir) = &cfg.artifacts {
        for f in &report.failures {
            let d = dir.join(format!("seed{}-program{}", cfg.seed, f.id));
            let _ = std::fs::create_dir_all(&d);
            let _ = std::fs::write(d.join("program.rs"), &f.source);
            let _ = std::fs::write(d.join("program.wgsl"), &f.wgsl);
            let _ = std::fs::write(d.join("report.txt"), &f.detail);
            if cfg.minimize_secs > 0 {
                let budget = Duration::from_secs(cfg.minimize_secs);
                let small = reduce::minimize(&gpu, cfg.seed, f, generate::program(cfg.seed, f.id), budget);
                let _ = std::fs::write(d.join("minimized.rs"), small.source());
                // How the reduced program fails.
                let mut r = Report { device: String::new(), stats: Stats::default(), failures: Vec::new() };
                match prepare_program(cfg.seed, f.id, small) {
                    Ok(p) => run_batch(&gpu, std::slice::from_ref(&p), &mut r),
                    Err(e) => r.failures.push(e),
                }
                let detail: Vec<&str> = r.failures.iter().map(|f| f.detail.as_str()).collect();
                let _ = std::fs::write(d.join("minimized.txt"), detail.join("\n"));
            }
        }
    }
    report
}

/// The heap layout of a batch: per program, its inputs, then its output
/// buffers.
fn layout(batch: &[Prepared]) -> (Vec<u32>, Vec<gpu::Slot>) {
    let mut heap = Vec::new();
    let mut slots = Vec::new();
    for p in batch {
        let input_base = heap.len() as u32;
        let input_words: u32 = p.program.inputs.iter().map(|(_, t)| p.program.words(t)).sum();
        for lane in &p.inputs {
            let mut words = Vec::new();
            for v in lane {
                v.words(&mut words);
            }
            heap.extend(words.iter().map(|w| match w {
                Word::Int(b, _) => *b,
                Word::Float(f, _) => f.to_bits(),
            }));
        }
        let mut buffers = Vec::new();
        for (_, t) in &p.program.outputs {
            let n = gpu::LANES * p.program.slots;
            buffers.push((heap.len() as u32, n));
            heap.extend(std::iter::repeat_n(0, (n * p.program.words(t)) as usize));
        }
        slots.push(gpu::Slot { input_base, input_words, buffers });
    }
    (heap, slots)
}

fn run_batch(gpu: &gpu::Gpu, batch: &[Prepared], report: &mut Report) {
    if batch.is_empty() {
        return;
    }
    let (heap, slots) = layout(batch);
    let parts: Vec<&rt_compiler::Lowered> = batch.iter().map(|p| &p.lowered).collect();
    let wgsl = gpu::assemble(&parts, &slots);
    match gpu.run(&wgsl, &heap, (1, batch.len() as u32, 1)) {
        Ok(out) => {
            for (p, s) in batch.iter().zip(&slots) {
                compare(p, s, &out, report);
            }
        }
        Err(_) if batch.len() > 1 => {
            // Find the programs at fault one by one.
            for p in batch {
                run_batch(gpu, std::slice::from_ref(p), report);
            }
        }
        Err(e) => report.failures.push(Failure {
            id: batch[0].id,
            program: batch[0].program.name.clone(),
            kind: "wgpu",
            detail: format!("the module does not run: {e}"),
            source: batch[0].source.clone(),
            wgsl,
        }),
    }
}

/// Whether the GPU's float `got` matches `want` within `err` (plus 2 ULP;
/// zeros of either sign and subnormals are equal).
pub fn float_matches(want: f32, err: f64, got: f32) -> bool {
    if !got.is_finite() {
        return false;
    }
    if want.to_bits() == got.to_bits() {
        return true;
    }
    if want.abs() < f32::MIN_POSITIVE && got.abs() < f32::MIN_POSITIVE {
        return true;
    }
    let diff = (want as f64 - got as f64).abs();
    diff <= err + 2.0 * interp::ulp(want.abs().max(got.abs()) as f64)
}

fn compare(p: &Prepared, slot: &gpu::Slot, heap: &[u32], report: &mut Report) {
    let mut diffs = Vec::new();
    for (lane, expected) in p.expected.iter().enumerate() {
        report.stats.lanes += 1;
        let bufs = match expected {
            Ok(b) => b,
            Err(Stop::NonFinite(_)) => {
                report.stats.lanes_non_finite += 1;
                continue;
            }
            Err(Stop::Diverged(_)) => {
                report.stats.lanes_diverged += 1;
                continue;
            }
        };
        for (b, words) in bufs.iter().enumerate() {
            let (offset, _) = slot.buffers[b];
            let base = offset as usize + lane * words.len();
            for (k, w) in words.iter().enumerate() {
                let got = heap[base + k];
                let ok = match *w {
                    Word::Int(_, true) => None,
                    Word::Int(x, false) => Some(x == got),
                    Word::Float(_, e) if !e.is_finite() => None,
                    Word::Float(f, e) => Some(float_matches(f, e, f32::from_bits(got))),
                };
                match ok {
                    None => report.stats.words_skipped += 1,
                    Some(true) => report.stats.words_compared += 1,
                    Some(false) => {
                        report.stats.words_compared += 1;
                        diffs.push((lane, b, k, *w, got));
                    }
                }
            }
        }
    }
    if diffs.is_empty() {
        return;
    }
    let mut d = String::new();
    let _ = writeln!(d, "program {} differs in {} words; the first ones:", p.id, diffs.len());
    let mut lanes_shown = Vec::new();
    // `RT_FUZZ_LANE=<launch index>` shows that launch index's differences.
    let only: Option<usize> = std::env::var("RT_FUZZ_LANE").ok().and_then(|l| l.parse().ok());
    for (lane, b, k, w, got) in diffs.iter().filter(|d| only.is_none_or(|l| l == d.0)).take(12) {
        let elem_words = p.program.words(&p.program.outputs[*b].1) as usize;
        let (elem, word) = (k / elem_words, k % elem_words);
        let want = match w {
            Word::Int(x, _) => format!("{x} ({:#x}, as i32 {})", x, *x as i32),
            Word::Float(f, e) => format!("{f:e} (+- {e:.3e})"),
        };
        let got_s = match w {
            Word::Int(..) => format!("{got} ({got:#x}, as i32 {})", *got as i32),
            Word::Float(..) => format!("{:e}", f32::from_bits(*got)),
        };
        let _ = writeln!(
            d,
            "  launch index {lane}: {}[slot + {elem}] word {word}: Rust {want}, GPU {got_s}",
            p.program.outputs[*b].0
        );
        if !lanes_shown.contains(lane) {
            lanes_shown.push(*lane);
        }
    }
    for lane in lanes_shown.iter().take(3) {
        let ins: Vec<String> =
            p.program.inputs.iter().zip(&p.inputs[*lane]).map(|((n, _), v)| format!("{n} = {}", show(v))).collect();
        let _ = writeln!(d, "  inputs of launch index {lane}: {}", ins.join(", "));
    }
    report.failures.push(Failure {
        id: p.id,
        program: p.program.name.clone(),
        kind: "mismatch",
        detail: d,
        source: p.source.clone(),
        wgsl: p.lowered.wgsl.clone(),
    });
}

/// The compiler's errors, each with the source line it points at.
fn located(e: &rt_compiler::Errors, source: &str) -> String {
    let lines: Vec<&str> = source.lines().collect();
    let mut out = String::new();
    for err in e.0.iter().filter(|e| !e.is_silent()) {
        let at = err.span.start();
        let line = lines.get(at.line.saturating_sub(1)).copied().unwrap_or("");
        let _ = writeln!(out, "error: {}\n  at line {}:{}: {}", err.message, at.line, at.column + 1, line.trim());
    }
    out
}

/// A value as Rust-like text.
pub fn show(v: &V) -> String {
    match v {
        V::B(b, _) => b.to_string(),
        V::I(i, _) => format!("{i}i32"),
        V::U(u, _) => format!("{u}u32"),
        V::F(f, _) => format!("{f:?}f32"),
        V::Vec(c) | V::Arr(c) | V::Struct(c) => {
            format!("[{}]", c.iter().map(show).collect::<Vec<_>>().join(", "))
        }
    }
}
