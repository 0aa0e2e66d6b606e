//! The compiler's differential fuzzer (see `rt_tests::fuzz`): at least 300
//! generated programs with a fixed seed, each run on the GPU (lavapipe
//! without one) as the compiler's WGSL and on the CPU by the interpreter,
//! results compared. `RT_FUZZ_PROGRAMS=5000 RT_FUZZ_SEED=7` runs more or
//! others; `RT_FUZZ_ONLY=<id>` one.

use rt_tests::fuzz;

#[test]
fn generated_programs_agree_on_cpu_and_gpu() {
    let mut cfg = fuzz::Config::from_env(0x5eed, 300);
    cfg.artifacts = Some(std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-fuzz"));
    let t = std::time::Instant::now();
    let report = fuzz::run(&cfg);
    eprintln!("{} ({:.1?} in all)", report.summary(), t.elapsed());
    if !report.failures.is_empty() {
        let mut msg = String::new();
        for f in report.failures.iter().take(5) {
            msg.push_str(&format!(
                "\n==== program {} ({}), seed {:#x}; rerun with RT_FUZZ_SEED={} RT_FUZZ_ONLY={}\n{}\n--- source\n{}",
                f.id, f.kind, cfg.seed, cfg.seed, f.id, f.detail, f.source
            ));
        }
        panic!("{} of {} programs fail:{msg}", report.failures.len(), report.stats.programs);
    }
}

/// The run above includes tuple literals read by `.0`/`.1`, values through
/// an `#[rt_enum]` (`FuzzKind`, matched exhaustively) and calls of
/// `#[rt_impl]` methods (`&mut self` ones among them), in a fair share of
/// its programs.
#[test]
fn the_fixed_seed_generates_tuples_enums_and_methods() {
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let (tuples, enums, methods, mut_self) = fuzz::on_big_stack(move || {
        let programs: Vec<fuzz::ast::Program> =
            (cfg.first..cfg.first + cfg.programs).map(|id| fuzz::generate::program(cfg.seed, id)).collect();
        let sources: Vec<String> = programs.iter().map(|p| p.source()).collect();
        let tuples = sources.iter().filter(|s| s.contains(",).0") || s.contains(",).1")).count();
        let enums = sources.iter().filter(|s| s.contains("FuzzKind::Alpha => 10u32")).count();
        // Programs that declare a method and call it.
        let called = |p: &fuzz::ast::Program, h: &fuzz::ast::Helper| {
            let call = format!(".{}(", h.name);
            let ufcs = format!("::{}(", h.name);
            let s = p.source();
            s.contains(&call) || s.contains(&ufcs)
        };
        let methods = programs.iter().filter(|p| p.helpers.iter().any(|h| h.method.is_some() && called(p, h))).count();
        let mut_self = programs
            .iter()
            .filter(|p| {
                p.helpers
                    .iter()
                    .any(|h| h.method.is_some_and(|m| m.receiver == fuzz::ast::Receiver::MutRef) && called(p, h))
            })
            .count();
        (tuples, enums, methods, mut_self)
    });
    let what = format!(
        "of 300 programs, {tuples} build tuples, {enums} match a FuzzKind, {methods} call #[rt_impl] methods \
         ({mut_self} a `&mut self` one)"
    );
    eprintln!("{what}");
    assert!(tuples >= 30 && enums >= 30 && methods >= 30 && mut_self >= 5, "{what}");
}

/// The run above includes methods of an `#[rt_trait]` (`FuzzOps`) and
/// operator traits (`Add`, `Sub`, `Mul`, `Mul<f32>`) implemented for a
/// struct and called, `(a + b)` or by name (`a.add(b)`), in a fair share
/// of its programs.
#[test]
fn the_fixed_seed_generates_trait_methods_and_operators() {
    use fuzz::ast::{Expr, Method, MethodForm, Program};
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let (traits, operators, scalar_rhs, by_name) = fuzz::on_big_stack(move || {
        let programs: Vec<Program> =
            (cfg.first..cfg.first + cfg.programs).map(|id| fuzz::generate::program(cfg.seed, id)).collect();
        // Whether `p` calls a method `is` accepts, in its body or a helper's.
        let calls = |p: &Program, is: &dyn Fn(Method) -> bool| {
            let mut found = false;
            let mut look = |e: &Expr| {
                if let Expr::Call(h, _) = e {
                    found |= p.helpers[*h].method.is_some_and(is);
                }
            };
            p.body.visit(&mut look);
            for h in &p.helpers {
                h.body.visit(&mut look);
            }
            found
        };
        let count = |is: &dyn Fn(Method) -> bool| programs.iter().filter(|p| calls(p, is)).count();
        (
            count(&|m| m.form == MethodForm::Trait),
            count(&|m| matches!(m.form, MethodForm::Operator(_))),
            count(&|m| matches!(m.form, MethodForm::Operator(op) if op.scalar_rhs())),
            count(&|m| matches!(m.form, MethodForm::Operator(_)) && m.ufcs),
        )
    });
    let what = format!(
        "of 300 programs, {traits} call a FuzzOps method, {operators} an operator impl ({scalar_rhs} `Mul<f32>`, \
         {by_name} by name)"
    );
    eprintln!("{what}");
    assert!(traits >= 15 && operators >= 30 && scalar_rhs >= 5 && by_name >= 5, "{what}");
}

/// The run above also includes bool vectors (`cmp*`, consumed by
/// `any`/`all`/`bitmask`/`select`), the dividing methods with any divisor
/// (method and path forms), integer vectors' `cross`/`manhattan_distance`,
/// NaN operands of comparisons and the vectors' `from_array`, std's integer
/// methods (`pow`, `isqrt`, `ilog2`, `abs_diff`, `midpoint`, ...).
#[test]
fn the_fixed_seed_generates_bool_vectors_dividing_methods_and_nan_operands() {
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let sources = fuzz::on_big_stack(move || {
        (cfg.first..cfg.first + cfg.programs)
            .map(|id| fuzz::generate::program(cfg.seed, id).source())
            .collect::<Vec<_>>()
    });
    let count = |forms: &[&str]| sources.iter().filter(|s| forms.iter().any(|f| s.contains(f))).count();
    let masks = count(&[".cmpeq(", ".cmpne(", ".cmplt(", ".cmple(", ".cmpgt(", ".cmpge("]);
    let consumed = count(&[".any()", ".all()", ".bitmask()", "::select("]);
    let dividing = count(&[".div_euclid(", ".rem_euclid(", ".wrapping_div(", ".saturating_div("]);
    let dividing_paths = count(&["::div_euclid(", "::rem_euclid(", "::wrapping_div(", "::saturating_div("]);
    let int_geometry = count(&[".manhattan_distance("]);
    let nan = count(&["f32::NAN"]);
    let from_array = count(&["::from_array(["]);
    let std_ints =
        count(&[".isqrt()", ".ilog2()", ".ilog10()", ".abs_diff(", ".midpoint(", ".pow(", "_pow(", ".wrapping_neg()"]);
    let what = format!(
        "of 300 programs, {masks} compare vectors into masks, {consumed} consume masks, {dividing} call dividing \
         methods ({dividing_paths} as paths), {int_geometry} measure integer distances, {nan} compare with NaN, \
         {from_array} build vectors with `from_array`, {std_ints} call std's integer methods"
    );
    eprintln!("{what}");
    assert!(
        masks >= 30
            && consumed >= 30
            && dividing >= 30
            && dividing_paths >= 10
            && int_geometry >= 10
            && nan >= 10
            && from_array >= 30
            && std_ints >= 30,
        "{what}"
    );
}

/// The interpreter against rustc: the generated programs built natively
/// (through the real macros, overflow checks off) and run with the same
/// inputs must give the interpreter's outputs. Builds a Cargo project of
/// its own (minutes); `RT_FUZZ_PROGRAMS` sets how many programs.
#[test]
#[ignore = "builds the generated programs with rustc (minutes); run with --ignored"]
fn interpreter_agrees_with_rustc() {
    let cfg = fuzz::Config::from_env(0x5eed, 150);
    fuzz::on_big_stack(move || {
        let programs: Vec<fuzz::Prepared> =
            (cfg.first..cfg.first + cfg.programs).filter_map(|id| fuzz::prepare(cfg.seed, id).ok()).collect();
        let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rt-fuzz-native");
        let rt_std = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../rt-std").canonicalize().unwrap();
        fuzz::native::write_project(&dir, &rt_std, &programs).unwrap();
        let out = std::process::Command::new(env!("CARGO"))
            .args(["run", "--release", "--quiet", "-j2"])
            .current_dir(&dir)
            .env("CARGO_TARGET_DIR", dir.join("target"))
            .output()
            .unwrap();
        assert!(out.status.success(), "the native build or run fails:\n{}", String::from_utf8_lossy(&out.stderr));
        let diffs = fuzz::native::compare(&programs, &String::from_utf8_lossy(&out.stdout));
        assert!(diffs.is_empty(), "{} differences:\n{}", diffs.len(), diffs[..diffs.len().min(40)].join("\n"));
        eprintln!("{} programs agree with rustc", programs.len());
    });
}

/// The fuzzer's minimized regressions (`snapshots/in/fuzz_regressions.rs`,
/// one per compiler bug it found) run natively, as rustc compiled them, and
/// on the GPU, as the compiler lowered them, with the same inputs: the
/// outputs must agree (integers exactly, floats within 2 ULP).
#[test]
fn regressions_agree_on_cpu_and_gpu() {
    use rt_std::cpu::{ExecutionContext, with_context};
    use rt_std::prelude::*;
    use rt_tests::fuzz::gpu::{Gpu, LANES, Slot, assemble};
    use rt_tests::fuzz_regressions as r;
    type Program = fn(u32, i32, f32, RwBuffer<u32>, RwBuffer<f32>);
    // (`fuzz_shift_amounts` overflows in a debug build: compiled only.)
    let programs: [(&str, Program); 8] = [
        ("fuzz_eval_order", r::fuzz_eval_order),
        ("fuzz_assign_order", r::fuzz_assign_order),
        ("fuzz_match_break", r::fuzz_match_break),
        ("fuzz_const_ints", r::fuzz_const_ints),
        ("fuzz_int_bool_ops", r::fuzz_int_bool_ops),
        ("fuzz_float_formulas", r::fuzz_float_formulas),
        ("fuzz_zero_vectors", r::fuzz_zero_vectors),
        ("fuzz_bitwise_compound", r::fuzz_bitwise_compound),
    ];
    let source = include_str!("../snapshots/in/fuzz_regressions.rs");
    let gpu = Gpu::new().expect("a wgpu adapter (lavapipe without a GPU)");
    let inputs: Vec<(u32, i32, f32)> =
        (0..LANES).map(|i| (i * 3 + i % 5, (i % 7) as i32 - 3, i as f32 * 0.75 - 10.0)).collect();
    let n = (LANES * r::SLOTS) as usize;
    let mut failures = Vec::new();
    for (name, program) in programs {
        let mut cpu_u = vec![0u32; n + 1];
        let mut cpu_f = vec![0f32; n + 1];
        for (lane, &(a, b, x)) in inputs.iter().enumerate() {
            // SAFETY: `n + 1` elements each (the last the out-of-bounds sink),
            // alive and otherwise untouched during the call.
            let (out_u, out_f) = unsafe {
                (
                    RwBuffer::from_raw_parts(cpu_u.as_mut_ptr(), n as u32),
                    RwBuffer::from_raw_parts(cpu_f.as_mut_ptr(), n as u32),
                )
            };
            let ctx = ExecutionContext {
                launch_index: uvec2(lane as u32, 0),
                launch_dim: uvec2(LANES, 1),
                ..Default::default()
            };
            with_context(ctx, || program(a, b, x, out_u, out_f));
        }
        let lowered = rt_compiler::lower_source(source, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut heap: Vec<u32> = inputs.iter().flat_map(|&(a, b, x)| [a, b as u32, x.to_bits()]).collect();
        let base = heap.len() as u32;
        heap.resize(heap.len() + 2 * n, 0);
        let slot = Slot { input_base: 0, input_words: 3, buffers: vec![(base, n as u32), (base + n as u32, n as u32)] };
        let wgsl = assemble(&[&lowered], &[slot]);
        let out = gpu.run(&wgsl, &heap, (1, 1, 1)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (gpu_u, gpu_f) = out[base as usize..].split_at(n);
        for i in 0..n {
            let lane = i / r::SLOTS as usize;
            if cpu_u[i] != gpu_u[i] {
                failures.push(format!("{name}: launch index {lane} out_u[{i}]: Rust {}, GPU {}", cpu_u[i], gpu_u[i]));
            }
            if !fuzz::float_matches(cpu_f[i], 0.0, f32::from_bits(gpu_f[i])) {
                failures.push(format!(
                    "{name}: launch index {lane} out_f[{i}]: Rust {}, GPU {}",
                    cpu_f[i],
                    f32::from_bits(gpu_f[i])
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures[..failures.len().min(30)].join("\n"));
}

/// The run above also loops over arrays as Rust writes it: by value, through
/// `.iter()`, reversed and numbered (`enumerate`), which the compiler
/// rewrites into counted loops.
#[test]
fn the_fixed_seed_generates_array_loops() {
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let sources = fuzz::on_big_stack(move || {
        (cfg.first..cfg.first + cfg.programs)
            .map(|id| fuzz::generate::program(cfg.seed, id).source())
            .collect::<Vec<_>>()
    });
    let count = |form: &str| sources.iter().filter(|s| s.contains(form)).count();
    let (iter, rev, numbered) = (count(".iter()"), count(".rev() "), count(".enumerate()"));
    let what =
        format!("of 300 programs, {iter} loop through `.iter()`, {rev} reversed, {numbered} with `.enumerate()`");
    eprintln!("{what}");
    assert!(iter >= 30 && rev >= 15 && numbered >= 15, "{what}");
}

/// The fixed seed calls the generic helper every program declares
/// (`fuzz_pick<T>`) in a fair share of its programs, several times in some
/// (at the types of their arguments).
#[test]
fn the_fixed_seed_calls_a_generic_helper() {
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let (some, several) = fuzz::on_big_stack(move || {
        let calls: Vec<usize> = (cfg.first..cfg.first + cfg.programs)
            .map(|id| fuzz::generate::program(cfg.seed, id).source().matches("fuzz_pick(").count())
            .collect();
        (calls.iter().filter(|&&n| n >= 1).count(), calls.iter().filter(|&&n| n >= 3).count())
    });
    let what = format!("of 300 programs, {some} call the generic `fuzz_pick`, {several} three times or more");
    eprintln!("{what}");
    assert!(some >= 30 && several >= 5, "{what}");
}

/// The fixed seed writes closures, `Option` flows (each of their four
/// forms: `unwrap_or`, `match`, `if let`, `filter`), iterator folds
/// (`fold`, `sum`, `.rev()`) and labelled loops left by a `break` from a
/// loop inside, in a fair share of its programs.
#[test]
fn the_fixed_seed_generates_closures_options_folds_and_labelled_breaks() {
    let cfg = fuzz::Config::from_env(0x5eed, 300);
    let forms = [
        "|fz_a",
        "fuzz_apply(|fz_a",
        ".unwrap_or(",
        "Some(fz_o",
        "if let Some(",
        ".filter(|_|",
        ".fold(",
        ".sum::<",
        ".rev().fold(",
        "break 'fz_l",
    ];
    let counts = fuzz::on_big_stack(move || {
        forms.map(|f| {
            (cfg.first..cfg.first + cfg.programs)
                .filter(|id| fuzz::generate::program(cfg.seed, *id).source().contains(f))
                .count()
        })
    });
    let what: Vec<String> = forms.iter().zip(counts).map(|(f, n)| format!("`{f}` in {n}")).collect();
    let what = format!("of 300 programs: {}", what.join(", "));
    eprintln!("{what}");
    assert!(counts[0] >= 20 && counts[1] >= 10 && counts[6] >= 10, "{what}");
    assert!(counts.iter().all(|&n| n >= 3), "{what}");
}
