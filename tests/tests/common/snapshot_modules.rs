//! The checked-in snapshots (`snapshots/out/*.wgsl`) as whole WGSL modules:
//! each with the compiler's stub prelude it was validated against, and a
//! tracing program's resumable form in place of its plain form with stubs
//! for what the linker gives it. Shared by the naga check (snapshots.rs)
//! and the Tint check (tint.rs).

use std::path::{Path, PathBuf};

/// Where a tracing program's snapshot goes on with its resumable form.
pub const RESUMABLE: &str = "\n// ---- resumable form ----\n";

/// The folder of `in/` and `out/`.
pub fn corpus_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("snapshots")
}

/// `(snapshot file, module)` for every checked-in snapshot, by file name.
pub fn modules() -> Vec<(PathBuf, String)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(corpus_dir().join("out"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "wgsl"))
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            let module = module_of(&path, &text);
            (path, module)
        })
        .collect()
}

fn module_of(path: &Path, text: &str) -> String {
    // A module over the atomic heap says so in its first line.
    let atomic = text.lines().next().is_some_and(|l| l.ends_with(" (atomic heap)"));
    let prelude = if atomic { &*rt_compiler::lower::ATOMIC_PRELUDE } else { &*rt_compiler::lower::PRELUDE };
    match text.split_once(RESUMABLE) {
        // The resumable form replaces the plain program, with stubs for
        // what the linker gives it.
        Some((plain, resumable)) => {
            let program = plain.rfind("\nfn rtp_").unwrap_or_else(|| panic!("{}: no plain program", path.display()));
            let mut stubs =
                String::from("var<private> rt_rs: u32;\nvar<private> rt_d: u32;\nconst RT_DEPTHS: u32 = 1u;\n");
            let mut payloads: Vec<&str> =
                resumable.split("rt_request_").skip(1).map(|t| t.split('(').next().unwrap_or(t)).collect();
            payloads.sort_unstable();
            payloads.dedup();
            for p in payloads {
                stubs.push_str(&format!(
                    "fn rt_request_{p}(object: u32, ray: RtRay, prd: {p}, flags: u32, mask: u32) {{}}\nfn rt_result_{p}() -> {p} {{\n    var p: {p};\n    return p;\n}}\n"
                ));
            }
            format!("{prelude}{}{stubs}{resumable}", &plain[..program])
        }
        None => format!("{prelude}{text}"),
    }
}
