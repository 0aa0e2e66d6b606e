//! A second WGSL implementation: every linked kernel of the tour, every
//! kernel the rest of the suite linked, and every checked-in snapshot with
//! its prelude go to Tint (Dawn's WGSL compiler, the one Chrome ships) via
//! Node and the npm package `webgpu` (`scripts/tint/check.mjs`). Any error
//! or warning fails the test, with its file, line and text. naga accepts
//! more than the WGSL specification does (a constant infinity, a decimal
//! just above `f32::MAX`): this is what keeps the kernels portable.
//!
//! scripts/test.sh installs Node's package, runs the suite with
//! `RT_WGSL_KERNEL_DIR` set (rt-runtime keeps every kernel it links
//! there), then runs this test with `RT_TINT=require`: there a missing
//! Node, package or kernel folder is a failure. Run by plain `cargo test`
//! on a machine without them, the test says what it skipped and why.

use dawn::MODE_VAR;
use rt_runtime::backend::wgpu::KERNEL_DIR_VAR;
use std::path::{Path, PathBuf};

#[path = "common/dawn.rs"]
mod dawn;
#[path = "common/snapshot_modules.rs"]
mod snapshot_modules;

/// The linked kernel of every tour example, rendered tiny on wgpu.
fn tour_kernels() -> Vec<(String, String)> {
    let settings = examples::Settings { backend: rt_runtime::Backend::Wgpu, ..examples::Settings::new(8, 6) };
    let settings = settings.with_spp(1);
    examples::EXAMPLES
        .iter()
        .map(|example| {
            let mut scene = (example.build)(&settings).unwrap_or_else(|e| panic!("{}: {e}", example.name));
            scene.render(&mut |_| {}).unwrap_or_else(|e| panic!("{} on wgpu: {e}", example.name));
            let wgsl = scene.ctx.linked_wgsl().unwrap_or_else(|| panic!("{}: no linked WGSL", example.name));
            (example.name.to_string(), wgsl.to_string())
        })
        .collect()
}

/// The kernels the suite kept in `RT_WGSL_KERNEL_DIR`, if set.
fn suite_kernels(required: bool) -> Vec<(String, String)> {
    let Some(dir) = std::env::var_os(KERNEL_DIR_VAR) else {
        assert!(!required, "{MODE_VAR}=require but {KERNEL_DIR_VAR} is not set: run scripts/test.sh");
        return Vec::new();
    };
    let dir = PathBuf::from(dir);
    let mut kernels: Vec<(String, String)> = match std::fs::read_dir(&dir) {
        Ok(entries) => entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
            .map(|p| {
                let text = std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
                (p.file_stem().unwrap_or_default().to_string_lossy().into_owned(), text)
            })
            .collect(),
        Err(e) => {
            assert!(!required, "{KERNEL_DIR_VAR}={}: {e} (did the suite run before this test?)", dir.display());
            Vec::new()
        }
    };
    kernels.sort();
    assert!(!required || kernels.len() >= 20, "{}: only {} kernels kept by the suite", dir.display(), kernels.len());
    kernels
}

#[test]
fn tint_accepts_every_kernel_and_snapshot() {
    if !dawn::available("the Tint check") {
        return;
    }
    let required = dawn::required();
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tint");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let mut counts = Vec::new();
    let snapshots = snapshot_modules::modules();
    for (path, module) in &snapshots {
        let stem = path.file_stem().unwrap_or_default().to_string_lossy();
        std::fs::write(out.join(format!("snapshot-{stem}.wgsl")), module).unwrap();
    }
    counts.push(("snapshots", snapshots.len()));
    let tour = tour_kernels();
    for (name, wgsl) in &tour {
        std::fs::write(out.join(format!("tour-{name}.wgsl")), wgsl).unwrap();
    }
    counts.push(("tour kernels", tour.len()));
    // Ray-query kernels are native wgpu only (`enable wgpu_ray_query;`:
    // WebGPU has no ray queries), so Tint is not given them.
    let (ray_query, suite): (Vec<_>, Vec<_>) =
        suite_kernels(required).into_iter().partition(|(_, wgsl)| wgsl.starts_with("enable wgpu_ray_query;"));
    for (name, wgsl) in &suite {
        std::fs::write(out.join(format!("suite-{name}.wgsl")), wgsl).unwrap();
    }
    counts.push(("suite kernels", suite.len()));
    eprintln!("tint: {} ray-query kernels of the suite left out (WebGPU has no ray queries)", ray_query.len());

    let (ok, stdout, stderr) = dawn::node("check.mjs", &[&out]);
    let total: usize = counts.iter().map(|(_, n)| n).sum();
    let summary: Vec<String> = counts.iter().map(|(what, n)| format!("{n} {what}")).collect();
    eprintln!("tint: {total} modules ({})", summary.join(", "));
    eprintln!("{}", stdout.trim_end());
    assert!(ok, "Tint rejected modules (in {}):\n{stdout}\n{stderr}", out.display());
    assert!(
        stdout.contains(&format!("tint: {total} modules checked, 0 rejected")),
        "check.mjs did not check all {total} modules:\n{stdout}"
    );
    assert!(snapshots.len() >= 25 && tour.len() == examples::EXAMPLES.len(), "{}", summary.join(", "));
}

/// The check can fail: the spellings Tint rejected before (a decimal above
/// `f32::MAX`, a constant infinity) are reported with their lines.
#[test]
fn tint_rejects_what_naga_lets_through() {
    if !dawn::available("the Tint check") {
        return;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tint-rejects");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    // Tint stops at a module's first error: one module per spelling.
    let modules = [
        ("old_max", "fn big() -> f32 {\n    return 3.4028235e38f;\n}\n"),
        ("old_inf", "fn inf() -> f32 {\n    let x = 1.0;\n    return x * bitcast<f32>(0x7f800000u);\n}\n"),
    ];
    for (name, module) in modules {
        naga::front::wgsl::parse_str(module).unwrap_or_else(|e| panic!("naga rejects {name}: {e}"));
        std::fs::write(out.join(format!("{name}.wgsl")), module).unwrap();
    }
    let (ok, stdout, _) = dawn::node("check.mjs", &[&out]);
    assert!(!ok, "Tint accepted:\n{stdout}");
    assert!(stdout.contains("old_max.wgsl:2:12: error"), "{stdout}");
    assert!(stdout.contains("old_inf.wgsl:3:16: error"), "{stdout}");
    assert!(stdout.contains("tint: 2 modules checked, 2 rejected"), "{stdout}");
}
