//! The compiler fuzzer's programs on the CPU backend, one launch index at a
//! time and lane-wise: `build.rs` writes the fixed seed's programs (300;
//! `RT_FUZZ_LANES_PROGRAMS` at build time sets how many) with each input
//! in a buffer of one value per launch index, so that one launch gives every
//! launch index the inputs the wgpu harness gives it and the program's
//! branches, loop trip counts and early returns differ from lane to lane.
//! Each program runs in both modes in the same test, whatever
//! `RT_CPU_EXEC` says, with a launch size that is often not a multiple of
//! the lane-wise block. The two runs must agree exactly (every word, the
//! exceptions), and both must give the fuzzer's interpreter's outputs
//! (integers exactly, floats within its error bound plus 2 ULP, the
//! interpreter's uncertain words and non-finite launch indices skipped), the
//! outputs `fuzz_compiler.rs` checks the wgpu side against with the same
//! inputs. Nearly every program must run lane-wise.

use rt_runtime::*;
use rt_std::RtData;
use rt_std::program::ProgramDescriptor;
use rt_tests::fuzz::{self, gpu::LANES, interp::Stop, interp::Word};

/// Reads an output buffer's words.
type Reader = Box<dyn Fn(&Context) -> Vec<u32>>;

/// A generated program: its id, its programs and its buffers' setup
/// (`setup(ctx, inputs)` binds them; the readers of the outputs, the ray
/// hashes last).
struct Fuzzed {
    id: usize,
    program: &'static ProgramDescriptor,
    hit: &'static ProgramDescriptor,
    miss: &'static ProgramDescriptor,
    setup: fn(&mut Context, &[Vec<u32>]) -> Vec<Reader>,
}

include!(concat!(env!("OUT_DIR"), "/fuzz_lanes.rs"));

/// Binds `fuzz_in`, a buffer of each launch index's `T` (read from its
/// words at `at`).
fn input<T: RtData + Send + Sync>(ctx: &mut Context, name: &str, inputs: &[Vec<u32>], at: usize) {
    let values: Vec<T> = inputs.iter().map(|w| T::read_words(&w[at..])).collect();
    let b = ctx.create_buffer(BufferType::InputOutput, values);
    ctx.set_var(Scope::Context, name, b).unwrap();
}

/// [`input`] for a `bool`, which the buffer holds as a `u32`.
fn input_bool(ctx: &mut Context, name: &str, inputs: &[Vec<u32>], at: usize) {
    input::<u32>(ctx, name, inputs, at);
}

/// Binds an output buffer of `slots` zeroed elements per launch index;
/// its reader.
fn output<T: RtData + Send + Sync>(ctx: &mut Context, name: &str, slots: u32) -> Reader {
    let zeros = vec![0u32; T::LAYOUT.words as usize];
    let b = ctx.create_buffer(BufferType::InputOutput, (0..LANES * slots).map(|_| T::read_words(&zeros)).collect());
    ctx.set_var(Scope::Context, name, b).unwrap();
    Box::new(move |ctx: &Context| {
        let mut words = Vec::new();
        for v in ctx.read_buffer::<T>(b).unwrap() {
            let mut w = vec![0u32; T::LAYOUT.words as usize];
            v.write_words(&mut w);
            words.extend(w);
        }
        words
    })
}

/// One run's output words per buffer (the ray hashes last), exceptions,
/// rays traced, and each of the three programs' way (`None`: lane-wise;
/// else why it runs one launch index at a time).
struct Run {
    outputs: Vec<Vec<u32>>,
    exceptions: Vec<(glam::UVec2, u32)>,
    rays: u64,
    ways: Vec<Option<String>>,
}

fn run(p: &Fuzzed, mode: CpuExecution, inputs: &[Vec<u32>], n: u32) -> Run {
    let mut ctx = Context::new();
    ctx.set_backend(Backend::Cpu);
    ctx.set_cpu_execution(mode);
    let rg = ctx.create_program(p.program);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(p.miss);
    ctx.set_miss_program(0, miss).unwrap();
    let mesh = ctx.create_triangles(rt_tests::meshes::bumpy_grid(5)).unwrap();
    let mat = ctx.create_material();
    let hit = ctx.create_program(p.hit);
    ctx.set_closest_hit_program(mat, 0, hit).unwrap();
    let gi = ctx.create_geometry_instance(mesh, &[mat]).unwrap();
    let top = ctx.create_geometry_group(&[gi], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "fuzz_top", top).unwrap();
    let readers = (p.setup)(&mut ctx, inputs);
    let report = ctx.launch(0, n, 1).unwrap_or_else(|e| panic!("program {}: {e}", p.id));
    let ways = ctx.cpu_execution();
    let way = |d: &ProgramDescriptor| ways.iter().find(|w| w.program == d.name).unwrap().scalar_because.clone();
    Run {
        outputs: readers.iter().map(|r| r(&ctx)).collect(),
        exceptions: report.exceptions.iter().map(|e| (e.launch_index, e.code)).collect(),
        rays: report.rays,
        ways: vec![way(p.program), way(p.hit), way(p.miss)],
    }
}

/// The launch sizes, in turn: most not a multiple of the block.
const SIZES: [u32; 5] = [LANES, LANES - 3, 13, 40, 7];

#[derive(Default)]
struct Tally {
    programs: usize,
    lane_wise: usize,
    scalar: Vec<String>,
    launch_indices: usize,
    /// Programs that traced, and the rays they traced.
    traces: usize,
    rays: u64,
    words_compared: usize,
    words_skipped: usize,
    failures: Vec<String>,
}

/// Checks program `p`: both modes agree exactly and with the interpreter.
fn check(p: &Fuzzed, tally: &mut Tally) {
    let prepared = fuzz::interpreted(SEED, p.id, fuzz::generate::lanes_variant(SEED, p.id));
    let inputs: Vec<Vec<u32>> = prepared
        .inputs
        .iter()
        .map(|lane| {
            let mut w = Vec::new();
            for v in lane {
                v.words(&mut w);
            }
            w.iter()
                .map(|w| match w {
                    Word::Int(b, _) => *b,
                    Word::Float(f, _) => f.to_bits(),
                })
                .collect()
        })
        .collect();
    let n = SIZES[p.id % SIZES.len()];
    let scalar = run(p, CpuExecution::Scalar, &inputs, n);
    let lanes = run(p, CpuExecution::Lanes, &inputs, n);
    tally.programs += 1;
    let fail = |what: String| format!("program {} (launch size {n}; RT_FUZZ_ONLY={}): {what}", p.id, p.id);
    tally.traces += usize::from(lanes.rays > 0);
    tally.rays += lanes.rays;
    for (what, way) in ["ray generation", "closest hit", "miss"].iter().zip(&lanes.ways) {
        match way {
            None if *what == "ray generation" => tally.lane_wise += 1,
            None => {}
            Some(why) => tally.scalar.push(format!("program {} ({what}): {why}", p.id)),
        }
    }
    if scalar.outputs != lanes.outputs {
        let first = (0..scalar.outputs.len())
            .flat_map(|b| (0..scalar.outputs[b].len()).map(move |k| (b, k)))
            .find(|&(b, k)| scalar.outputs[b][k] != lanes.outputs[b][k]);
        tally.failures.push(fail(format!("scalar and lane-wise outputs differ, first at (buffer, word) {first:?}")));
    }
    if (&scalar.exceptions, scalar.rays) != (&lanes.exceptions, lanes.rays) {
        tally.failures.push(fail(format!(
            "exceptions or ray counts differ: scalar {:?} {}, lane-wise {:?} {}",
            scalar.exceptions, scalar.rays, lanes.exceptions, lanes.rays
        )));
    }
    let prog = &prepared.program;
    for lane in 0..n as usize {
        tally.launch_indices += 1;
        let expected = match &prepared.expected[lane] {
            Ok(e) => e,
            Err(Stop::NonFinite(_) | Stop::Diverged(_)) => continue,
        };
        for (b, want) in expected.iter().enumerate() {
            let per_lane = (prog.words(&prog.outputs[b].1) * prog.slots) as usize;
            let got = &lanes.outputs[b][lane * per_lane..(lane + 1) * per_lane];
            for (k, (w, g)) in want.iter().zip(got).enumerate() {
                let ok = match *w {
                    Word::Int(_, true) => None,
                    Word::Int(x, false) => Some(x == *g),
                    Word::Float(_, e) if !e.is_finite() => None,
                    Word::Float(f, e) => Some(fuzz::float_matches(f, e, f32::from_bits(*g))),
                };
                match ok {
                    None => tally.words_skipped += 1,
                    Some(ok) => {
                        tally.words_compared += 1;
                        if !ok {
                            tally.failures.push(fail(format!(
                                "launch index {lane} {}[word {k}]: interpreter {w:?}, CPU {g:#x} ({:e})",
                                prog.outputs[b].0,
                                f32::from_bits(*g)
                            )));
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn generated_programs_agree_lane_wise_scalar_and_with_the_interpreter() {
    let only: Option<usize> = std::env::var("RT_FUZZ_ONLY").ok().and_then(|v| v.parse().ok());
    let t = std::time::Instant::now();
    let tally = fuzz::on_big_stack(move || {
        let mut tally = Tally::default();
        for p in PROGRAMS.iter().filter(|p| only.is_none_or(|id| id == p.id)) {
            check(p, &mut tally);
        }
        tally
    });
    eprintln!(
        "{} programs of seed {SEED:#x} ({} lane-wise, {} tracing {} rays), {} launch indices, {} words compared with \
         the interpreter ({} uncertain ones skipped), {} failures ({:.1?})",
        tally.programs,
        tally.lane_wise,
        tally.traces,
        tally.rays,
        tally.launch_indices,
        tally.words_compared,
        tally.words_skipped,
        tally.failures.len(),
        t.elapsed()
    );
    for s in tally.scalar.iter().take(10) {
        eprintln!("  one launch index at a time: {s}");
    }
    assert!(tally.failures.is_empty(), "{}", tally.failures[..tally.failures.len().min(20)].join("\n"));
    if only.is_none() && option_env!("RT_FUZZ_LANES_PROGRAMS").is_none() {
        assert!(tally.programs >= 300, "{} programs", tally.programs);
    }
    assert!(tally.lane_wise * 10 >= tally.programs * 9, "only {} of {} run lane-wise", tally.lane_wise, tally.programs);
    assert!(tally.traces * 2 >= tally.programs, "only {} of {} programs trace", tally.traces, tally.programs);
}
