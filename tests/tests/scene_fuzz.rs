//! The scene-graph fuzzer (see `rt_tests::scene_fuzz`): 200
//! generated graphs with a fixed seed, each rendered on the CPU backend and
//! on wgpu (lavapipe without a GPU), hits compared per launch index.
//! `RT_SCENE_FUZZ=2000 RT_SCENE_FUZZ_SEED=7` runs more or others;
//! `RT_SCENE_FUZZ_ONLY=<index>` one.

use rt_tests::scene_fuzz;

#[test]
fn generated_graphs_agree_on_cpu_and_wgpu() {
    let cfg = scene_fuzz::Config::from_env(0x5ce7e, 200);
    let t = std::time::Instant::now();
    let report = scene_fuzz::run(&cfg);
    eprintln!("{} ({:.1?} in all)", report.summary(), t.elapsed());
    if !report.failures.is_empty() {
        let mut msg = String::new();
        for f in report.failures.iter().take(3) {
            msg.push_str(&format!(
                "\n==== graph {}, seed {:#x}; rerun with RT_SCENE_FUZZ_SEED={} RT_SCENE_FUZZ_ONLY={}\n{}--- graph\n{}",
                f.index, cfg.seed, cfg.seed, f.index, f.detail, f.description
            ));
        }
        panic!("{} of {} graphs disagree:{msg}", report.failures.len(), report.stats.graphs);
    }
}
