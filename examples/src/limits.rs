//! The loader's bounds as `render` and `viewer` flags: one clap group over
//! [`rt_scene::LoadLimits`], its defaults unless a flag says otherwise.

use rt_scene::LoadLimits;
use std::path::PathBuf;

/// What loading a model may read and allocate (see
/// [`rt_scene::LoadLimits`]); each refusal names its flag's field.
#[derive(Clone, Debug, Default, PartialEq, clap::Args)]
pub struct LimitArgs {
    /// A folder besides the model's own that its buffer and image URIs
    /// and `mtllib`s may name files in (repeatable).
    #[arg(long, value_name = "DIR")]
    pub allow_path: Vec<PathBuf>,
    /// Largest file read (the model, a buffer, an image, an `.mtl`), MiB
    /// (default 1024).
    #[arg(long, value_name = "MIB")]
    pub max_file_mib: Option<u64>,
    /// All of a glTF file's buffers together, MiB (default 1024).
    #[arg(long, value_name = "MIB")]
    pub max_buffer_mib: Option<u64>,
    /// All textures' pixels together (default 33554432, two 4096x4096).
    #[arg(long, value_name = "N")]
    pub max_texture_pixels: Option<u64>,
    /// Triangles shown, counting each instance (default 100000000).
    #[arg(long, value_name = "N")]
    pub max_triangles: Option<u64>,
    /// Nodes that show a mesh (default 1000000).
    #[arg(long, value_name = "N")]
    pub max_instances: Option<u64>,
}

impl LimitArgs {
    /// The limits these flags set.
    pub fn limits(&self) -> LoadLimits {
        let mut l = LoadLimits { allowed_dirs: self.allow_path.clone(), ..LoadLimits::default() };
        if let Some(mib) = self.max_file_mib {
            l.max_file_bytes = mib.saturating_mul(1 << 20);
        }
        if let Some(mib) = self.max_buffer_mib {
            l.max_buffer_bytes = mib.saturating_mul(1 << 20);
            l.max_data_uri_bytes = l.max_data_uri_bytes.min(l.max_buffer_bytes);
        }
        if let Some(n) = self.max_texture_pixels {
            l.max_texture_pixels = n;
            l.max_texture_bytes = n.saturating_mul(16);
        }
        if let Some(n) = self.max_triangles {
            l.max_triangles = n;
        }
        if let Some(n) = self.max_instances {
            l.max_instances = n;
        }
        l
    }
}
