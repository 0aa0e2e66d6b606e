//! Files: a texture that cannot be read, an image that cannot be written.

/// A file the runtime reads or writes that cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// A texture that could not be read or used.
    #[error("texture {path}: {problem}")]
    Texture {
        /// The texture's file.
        path: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// An image that could not be written.
    #[error("writing {path}: {problem}")]
    Image {
        /// The image file.
        path: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
}
