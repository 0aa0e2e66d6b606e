//! What a file may make the loader read and allocate: [`LoadLimits`], and
//! the file reads that honour it ([`read_file`], [`resolve`]).
//!
//! Scene files come from strangers. Without bounds a 36 KB GLB holding a
//! 16384x16384 one-bit PNG decodes into gigabytes, a buffer URI naming
//! `/dev/zero` reads until memory runs out, a FIFO blocks for ever, and a
//! URI of `../../home/me/.ssh/id_rsa` puts another file's bytes into the
//! picture. So every file is read only when it is a regular file no
//! larger than a bound, relative URIs resolve only inside the model's
//! folder (or folders the user allows), and sizes are checked from
//! headers before anything is decoded. Each refusal names the file, the
//! object and the limit (`LoadLimits::max_texture_pixels`), so a user who
//! trusts a large file knows which bound to raise.

use crate::clip::clip_path;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Bounds on what loading one scene may read and allocate. The defaults
/// (`LoadLimits::default()`) take any scene a workstation renders
/// comfortably and refuse what would exhaust one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadLimits {
    /// Bytes of any one file read: the model, a buffer, an image, an
    /// `.mtl`. Default 1 GiB.
    pub max_file_bytes: u64,
    /// Bytes of all of a glTF file's buffers together. Default 1 GiB.
    pub max_buffer_bytes: u64,
    /// Decoded bytes of one `data:` URI. Default 256 MiB.
    pub max_data_uri_bytes: u64,
    /// Pixels of all textures together, checked from each image's header
    /// before it is decoded. Default 32 Mi (two 4096x4096 textures).
    pub max_texture_pixels: u64,
    /// Bytes of all textures together as the loader keeps them (linear
    /// RGBA f32, 16 bytes a pixel), checked from each image's header.
    /// Default 512 MiB.
    pub max_texture_bytes: u64,
    /// Triangles as seen, counting each instance. Default 100 million.
    pub max_triangles: u64,
    /// Nodes that show a mesh. Default 1 million.
    pub max_instances: u64,
    /// Nodes of the hierarchy visited (after instancing). Default 1
    /// million.
    pub max_nodes: u64,
    /// Folders besides the model's own that its URIs and `mtllib`s may
    /// name files in (the model's folder is always allowed).
    pub allowed_dirs: Vec<PathBuf>,
}

impl Default for LoadLimits {
    fn default() -> Self {
        LoadLimits {
            max_file_bytes: 1 << 30,
            max_buffer_bytes: 1 << 30,
            max_data_uri_bytes: 256 << 20,
            max_texture_pixels: 32 << 20,
            max_texture_bytes: 512 << 20,
            max_triangles: 100_000_000,
            max_instances: 1_000_000,
            max_nodes: 1_000_000,
            allowed_dirs: Vec::new(),
        }
    }
}

impl LoadLimits {
    /// No bounds and every folder allowed: for files the caller trusts.
    pub fn unlimited() -> Self {
        LoadLimits {
            max_file_bytes: u64::MAX,
            max_buffer_bytes: u64::MAX,
            max_data_uri_bytes: u64::MAX,
            max_texture_pixels: u64::MAX,
            max_texture_bytes: u64::MAX,
            max_triangles: u64::MAX,
            max_instances: u64::MAX,
            max_nodes: u64::MAX,
            allowed_dirs: vec![PathBuf::from("/")],
        }
    }
}

/// `count` against `limit` (named as the field, `max_triangles`): the
/// refusal's text, or `None` within it.
pub fn over(what: &str, count: u64, limit: u64, name: &str) -> Option<String> {
    (count > limit).then(|| format!("{what} is {count}, over the limit of {limit} (LoadLimits::{name})"))
}

/// The bytes of the regular file at `path`, at most `limits.max_file_bytes`
/// of them; the error is one phrase (`no such file`, `not a regular file`,
/// the limit).
pub fn read_file(path: &Path, limits: &LoadLimits) -> Result<Vec<u8>, String> {
    // Looked at before it is opened: opening a FIFO blocks until a writer
    // comes; then the opened file is looked at again.
    if !std::fs::metadata(path).map_err(|e| reason(&e))?.is_file() {
        return Err("not a regular file".into());
    }
    let file = std::fs::File::open(path).map_err(|e| reason(&e))?;
    let meta = file.metadata().map_err(|e| reason(&e))?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if let Some(problem) = over("its size in bytes", meta.len(), limits.max_file_bytes, "max_file_bytes") {
        return Err(problem);
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // A file that grows while read is cut at the bound, then refused.
    file.take(limits.max_file_bytes.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| reason(&e))?;
    if let Some(problem) = over("its size in bytes", bytes.len() as u64, limits.max_file_bytes, "max_file_bytes") {
        return Err(problem);
    }
    Ok(bytes)
}

/// [`read_file`] as UTF-8 text.
pub fn read_text(path: &Path, limits: &LoadLimits) -> Result<String, String> {
    String::from_utf8(read_file(path, limits)?).map_err(|_| "it is not UTF-8 text".into())
}

/// `relative` (a URI's path or an `mtllib` name) looked up in `dir`, the
/// model's folder: the path, if it lies inside that folder or one of
/// `limits.allowed_dirs` once links and `..` are resolved.
pub fn resolve(dir: Option<&Path>, relative: &str, limits: &LoadLimits) -> Result<PathBuf, String> {
    let dir = dir.filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let path = dir.join(relative);
    let real = path.canonicalize().map_err(|e| format!("{}: {}", clip_path(&path), reason(&e)))?;
    let inside = |d: &Path| d.canonicalize().is_ok_and(|d| real.starts_with(d));
    if inside(dir) || limits.allowed_dirs.iter().any(|d| inside(d)) {
        Ok(path)
    } else {
        Err(format!(
            "{} is outside the model's folder {} (allow its folder with LoadLimits::allowed_dirs, `--allow-path DIR`)",
            clip_path(&path),
            dir.display()
        ))
    }
}

fn reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".into(),
        _ => e.to_string(),
    }
}
