//! Launch capture, for replaying a launch on another WebGPU implementation
//! (tests/tests/dawn_replay.rs runs it on Dawn): the kernel, every
//! binding's words as the launch found them, the tiles' uniforms and
//! workgroup counts, and what the launch produced (the output buffers'
//! words, the rays traced). Off unless [`capture_launches_to`] names a
//! folder; then every wgpu launch of the process overwrites its files:
//!
//! - `kernel.wgsl`;
//! - `binding<N>.bin`: the little-endian words of binding N (0 the heap,
//!   1 and from 4 up the scene, 2 the log), 3 (the launch uniform) comes
//!   per tile in `launch.json`;
//! - `outputs.bin`: the output buffers' words after the launch, in the
//!   order of `launch.json`'s `outputs` (`[heap offset, words]`);
//! - `launch.json`: `{"tiles": [[uniform words], gx, gy]..., "outputs":
//!   ..., "rays": N}`.

use super::dispatch::Tile;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

static FOLDER: Mutex<Option<PathBuf>> = Mutex::new(None);

/// Makes every later wgpu launch of this process write its capture to
/// `folder` (`None`: stop). For tests that replay launches elsewhere.
pub fn capture_launches_to(folder: Option<PathBuf>) {
    *FOLDER.lock().unwrap_or_else(|e| e.into_inner()) = folder;
}

/// The folder launches are captured to, if any.
pub(crate) fn folder() -> Option<PathBuf> {
    FOLDER.lock().unwrap_or_else(|e| e.into_inner()).clone()
}

/// What a launch found on the device, kept until it has run.
pub(crate) struct Before {
    pub folder: PathBuf,
    pub kernel: String,
    /// `(binding, words)`.
    pub bindings: Vec<(u32, Vec<u32>)>,
    pub tiles: Vec<Tile>,
}

fn bytes(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// Writes the capture of a launch that ran: `before`, the outputs'
/// `(buffer, heap offset, words)` and their words after it, the rays.
/// A capture that cannot be written says so on stderr; the launch stands.
pub(crate) fn write(before: &Before, outputs: &[(usize, usize, usize)], words: &[u32], rays: u32) {
    if let Err(e) = try_write(before, outputs, words, rays) {
        eprintln!("rt-runtime: launch capture in {}: {e}", before.folder.display());
    }
}

fn try_write(before: &Before, outputs: &[(usize, usize, usize)], words: &[u32], rays: u32) -> std::io::Result<()> {
    let dir: &Path = &before.folder;
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join("kernel.wgsl"), &before.kernel)?;
    for (binding, w) in &before.bindings {
        std::fs::write(dir.join(format!("binding{binding}.bin")), bytes(w))?;
    }
    // The read-back's words go on past the outputs (the log's header).
    let n: usize = outputs.iter().map(|o| o.2).sum();
    std::fs::write(dir.join("outputs.bin"), bytes(&words[..n.min(words.len())]))?;
    let tiles: Vec<String> = before
        .tiles
        .iter()
        .map(|(u, gx, gy)| {
            let u: Vec<String> = u.iter().map(|w| w.to_string()).collect();
            format!("[[{}], {gx}, {gy}]", u.join(", "))
        })
        .collect();
    let outs: Vec<String> = outputs.iter().map(|(_, offset, n)| format!("[{offset}, {n}]")).collect();
    let json = format!("{{\"tiles\": [{}], \"outputs\": [{}], \"rays\": {rays}}}\n", tiles.join(", "), outs.join(", "));
    std::fs::write(dir.join("launch.json"), json)
}
