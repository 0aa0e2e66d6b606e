//! Why a scene could not be loaded. Every error names the file; glTF errors
//! also name the object at fault in the document's own terms
//! (`meshes[2].primitives[0]`, `accessors[5]`, `buffers[0]`), so a user can
//! find it in the JSON.

use crate::obj::MeshError;
use rt_runtime::RtError;
use std::fmt;

/// A glTF file that cannot be used: the file, the object, the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GltfError {
    /// The file, as the caller named it.
    pub file: String,
    /// The glTF object at fault, as a JSON path (`meshes[2].primitives[0]`),
    /// or `None` when the problem is with the file as a whole.
    pub object: Option<String>,
    /// What is wrong, in a sentence.
    pub problem: String,
}

impl fmt::Display for GltfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.object {
            Some(object) => write!(f, "{}: {object}: {}", self.file, self.problem),
            None => write!(f, "{}: {}", self.file, self.problem),
        }
    }
}

impl std::error::Error for GltfError {}

/// Everything [`crate::load`] can refuse.
#[derive(Debug)]
pub enum SceneError {
    /// An OBJ (or its `.mtl`) with a problem, with its line when known.
    Obj(MeshError),
    /// A glTF or GLB file with a problem.
    Gltf(GltfError),
    /// A file whose extension names no format this crate reads.
    UnknownFormat {
        /// The file, as the caller named it.
        file: String,
    },
    /// The runtime refused what the file describes (a singular transform,
    /// say): the file and the runtime's reason.
    Runtime {
        /// The file (with the animation time, for a pose).
        file: String,
        /// The runtime's own error.
        error: Box<RtError>,
    },
    /// A panic while loading the file, caught at [`crate::load`]'s
    /// boundary: a bug of the loader (or a crate it uses), which the file
    /// triggered.
    Internal {
        /// The file, as the caller named it.
        file: String,
        /// The panic's message.
        message: String,
    },
}

impl SceneError {
    /// Whether the input is at fault (a bad or unsupported file, or one
    /// that made the loader panic) rather than the runtime: the binaries
    /// exit 2 for these, with the error as their one line.
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, SceneError::Runtime { .. })
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Obj(e) => e.fmt(f),
            SceneError::Gltf(e) => e.fmt(f),
            SceneError::UnknownFormat { file } => {
                write!(f, "{file}: not a scene format this build reads (expected .obj, .gltf or .glb)")
            }
            SceneError::Runtime { file, error } => write!(f, "{file}: {error}"),
            SceneError::Internal { file, message } => {
                write!(f, "{file}: internal error while loading (a bug; please report it): {}", first_line(message))
            }
        }
    }
}

impl std::error::Error for SceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SceneError::Obj(e) => Some(e),
            SceneError::Gltf(e) => Some(e),
            SceneError::Runtime { error, .. } => Some(error.as_ref()),
            SceneError::UnknownFormat { .. } | SceneError::Internal { .. } => None,
        }
    }
}

/// A panic message's first line, so the error stays one line.
fn first_line(message: &str) -> &str {
    message.lines().next().unwrap_or_default()
}

impl From<MeshError> for SceneError {
    fn from(e: MeshError) -> Self {
        SceneError::Obj(e)
    }
}

impl From<GltfError> for SceneError {
    fn from(e: GltfError) -> Self {
        SceneError::Gltf(e)
    }
}
