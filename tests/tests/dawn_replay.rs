//! One launch of every tour example, run on wgpu and replayed on Dawn
//! (Chrome's WebGPU implementation: Tint compiles the kernel, Dawn's
//! Vulkan backend runs it on lavapipe): the same kernel, bindings and
//! dispatches (rt-runtime's launch capture), the outputs compared within
//! the tolerance below and the rays traced compared exactly. Prints the
//! agreement figures per example. Skips like tint.rs where Node or the
//! package is missing, unless scripts/test.sh requires it.

use std::path::Path;

#[path = "common/dawn.rs"]
mod dawn;

/// The largest difference allowed between an output word of wgpu and of
/// Dawn, read as f32 (absolute, or relative above 1): both run the same
/// arithmetic on the same device through different compilers (naga and
/// Tint), which may contract or reorder float operations differently.
const TOLERANCE: f32 = 2e-3;

const W: u32 = 32;
const H: u32 = 24;

fn floats(path: &Path) -> Vec<f32> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

/// Agreement of two runs' output words.
struct Agreement {
    words: usize,
    identical: usize,
    within: usize,
    max_diff: f32,
}

fn agreement(wgpu: &[f32], dawn: &[f32]) -> Agreement {
    let mut a = Agreement { words: wgpu.len(), identical: 0, within: 0, max_diff: 0.0 };
    for (x, y) in wgpu.iter().zip(dawn) {
        if x.to_bits() == y.to_bits() {
            a.identical += 1;
            a.within += 1;
            continue;
        }
        let diff = (x - y).abs() / x.abs().max(1.0);
        a.max_diff = if diff.is_nan() { f32::INFINITY } else { a.max_diff.max(diff) };
        a.within += (diff <= TOLERANCE) as usize;
    }
    a
}

/// The `"rays": N` of a capture's launch.json.
fn captured_rays(dir: &Path) -> u64 {
    let json = std::fs::read_to_string(dir.join("launch.json")).unwrap();
    let tail = json.split("\"rays\": ").nth(1).expect("rays in launch.json");
    tail.trim_end_matches(|c: char| !c.is_ascii_digit()).parse().expect("a ray count")
}

#[test]
fn every_tour_example_replayed_on_dawn_agrees_with_wgpu() {
    if !dawn::available("the replay on Dawn") {
        return;
    }
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("dawn-replay");
    let _ = std::fs::remove_dir_all(&root);
    let settings = examples::Settings { backend: rt_runtime::Backend::Wgpu, ..examples::Settings::new(W, H) };
    let settings = settings.with_spp(1);
    let mut failures = Vec::new();
    for example in &examples::EXAMPLES {
        let dir = root.join(example.name);
        let mut scene = (example.build)(&settings).unwrap_or_else(|e| panic!("{}: {e}", example.name));
        rt_runtime::backend::wgpu::capture_launches_to(Some(dir.clone()));
        let rendered = scene.render(&mut |_| {});
        rt_runtime::backend::wgpu::capture_launches_to(None);
        let rendered = rendered.unwrap_or_else(|e| panic!("{} on wgpu: {e}", example.name));
        assert!(rendered.exceptions.is_empty(), "{} raised {:?} on wgpu", example.name, rendered.exceptions);
        let (ok, stdout, stderr) = dawn::node("replay.mjs", &[&dir]);
        assert!(ok, "{}: the replay on Dawn failed:\n{stdout}\n{stderr}", example.name);
        let rays: u64 = stdout
            .split("rays ")
            .nth(1)
            .and_then(|t| t.split(',').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{}: no ray count from replay.mjs:\n{stdout}", example.name));
        let wgpu = floats(&dir.join("outputs.bin"));
        let dawn = floats(&dir.join("dawn_outputs.bin"));
        assert_eq!(wgpu.len(), dawn.len(), "{}: output words", example.name);
        assert!(!wgpu.is_empty(), "{}: no output words", example.name);
        let a = agreement(&wgpu, &dawn);
        let wgpu_rays = captured_rays(&dir);
        eprintln!(
            "dawn replay {:<12} rays wgpu {wgpu_rays} dawn {rays}; {} words: {} identical, {} within {TOLERANCE}, max difference {:.3e}",
            example.name, a.words, a.identical, a.within, a.max_diff
        );
        if rays != wgpu_rays || a.within != a.words {
            failures.push(format!(
                "{}: rays {wgpu_rays} (wgpu) vs {rays} (Dawn); {} of {} words differ by more than {TOLERANCE} (max {:.3e})",
                example.name,
                a.words - a.within,
                a.words,
                a.max_diff
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
