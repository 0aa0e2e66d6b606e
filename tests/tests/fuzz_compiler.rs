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
