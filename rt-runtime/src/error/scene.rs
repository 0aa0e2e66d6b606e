//! The scene: a handle, a geometry, a transform, a buffer, a sampler or
//! the graph that cannot be used as given, and the acceleration built
//! over it.

/// An object of the scene (or a handle to one) that cannot be used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A handle (the `Debug` spelling given) that is not of this context.
    #[error("{0} is not a valid handle of this context")]
    InvalidHandle(String),
    /// A geometry that cannot be used (bad indices, no materials, ...).
    #[error("geometry {geometry}: {problem}")]
    BadGeometry {
        /// The geometry, by index.
        geometry: u32,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A transform that cannot be used (a singular matrix, bad motion keys, ...).
    #[error("transform: {problem}")]
    BadTransform {
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A buffer used wrongly (its type, size or index).
    #[error("buffer {buffer}: {problem}")]
    BadBuffer {
        /// The buffer, by index.
        buffer: u32,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A sampler used wrongly (its extent, format or mip levels).
    #[error("sampler {sampler}: {problem}")]
    BadSampler {
        /// The sampler, by index.
        sampler: u32,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A scene graph with a cycle.
    #[error("the scene graph has a cycle through node {node}")]
    GraphCycle {
        /// A node on the cycle.
        node: u32,
    },
    /// An acceleration builder that cannot be honoured.
    #[error("acceleration builder `{builder}` cannot be honoured: {reason}")]
    UnsupportedBuilder {
        /// The builder's name.
        builder: &'static str,
        /// Why it cannot be built.
        reason: &'static str,
    },
    /// A bounding-box program that gave a non-finite or inverted box.
    #[error(
        "bounding-box program `{program}` ({location}) gave primitive {primitive} of geometry {geometry} the box {bounds}, with {problem}; a box must be finite with min <= max on every axis"
    )]
    BadBounds {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The geometry, by index.
        geometry: u32,
        /// The primitive, by index.
        primitive: u32,
        /// The box (`min (x, y, z) max (x, y, z)`).
        bounds: String,
        /// What is wrong with the box.
        problem: &'static str,
    },
}
