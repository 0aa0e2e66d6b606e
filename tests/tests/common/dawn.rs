//! Dawn (Chrome's WebGPU implementation, with its WGSL compiler Tint) for
//! Node: the npm package `webgpu` in `scripts/tint`, which scripts/test.sh
//! installs. Shared by the Tint check (tint.rs) and the replay on Dawn
//! (dawn_replay.rs).

use std::path::{Path, PathBuf};
use std::process::Command;

/// `RT_TINT=require` (scripts/test.sh): a check that cannot run fails.
pub const MODE_VAR: &str = "RT_TINT";

/// Whether the checks must run (scripts/test.sh says so).
pub fn required() -> bool {
    std::env::var(MODE_VAR).is_ok_and(|v| v == "require")
}

/// `scripts/tint`: the package and its scripts.
pub fn tint_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/tint")
}

/// Why Dawn cannot run here, if it cannot.
pub fn missing_tools() -> Option<String> {
    match Command::new("node").arg("--version").output() {
        Ok(o) if o.status.success() => {}
        _ => return Some("`node` is not on PATH".into()),
    }
    let package = tint_dir().join("node_modules/webgpu/package.json");
    if !package.exists() {
        return Some(format!("{} is missing (npm ci --prefix scripts/tint)", package.display()));
    }
    None
}

/// False (after saying why) when the check cannot run and need not; a
/// panic when it cannot run and must.
pub fn available(check: &str) -> bool {
    match missing_tools() {
        None => true,
        Some(why) => {
            assert!(!required(), "{MODE_VAR}=require but {check} cannot run: {why}");
            eprintln!("{check}: skipped, {why} (scripts/test.sh installs it and requires the check)");
            false
        }
    }
}

/// Runs `node scripts/tint/<script> args...`: (success, stdout, stderr).
pub fn node(script: &str, args: &[&Path]) -> (bool, String, String) {
    let run = Command::new("node")
        .arg(tint_dir().join(script))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("node {script}: {e}"));
    (
        run.status.success(),
        String::from_utf8_lossy(&run.stdout).into_owned(),
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}
