//! Launches: a launch of an impossible size, a program or the runtime that
//! panicked while it ran, and a launch its progress callback cancelled.

/// A launch that could not run or did not finish; none wrote its outputs.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LaunchError {
    /// A launch of an impossible size or part.
    #[error("launch of {width}x{height}: {problem}")]
    BadLaunch {
        /// The launch's width.
        width: u32,
        /// The launch's height.
        height: u32,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A user program that panicked on the CPU backend; the launch wrote no outputs.
    #[error(
        "program `{program}` ({location}) panicked at launch index {launch_index} ({at}): {message}; the launch wrote none of its outputs"
    )]
    ProgramPanicked {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The launch index it ran for.
        launch_index: glam::UVec2,
        /// The panic's message.
        message: String,
        /// Where the panic happened (`file:line:column`), in the program or
        /// in code it called.
        at: String,
    },
    /// A bounding-box program that panicked; nothing was built.
    #[error(
        "bounding-box program `{program}` ({location}) panicked for primitive {primitive} ({at}): {message}; nothing was built"
    )]
    BoundsPanicked {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The primitive, by index.
        primitive: u32,
        /// The panic's message.
        message: String,
        /// Where the panic happened (`file:line:column`).
        at: String,
    },
    /// A panic inside the runtime during a launch (a bug in rt-runtime).
    #[error(
        "the {backend} backend panicked during the launch ({at}): {message}; this is a bug in rt-runtime; the launch wrote none of its outputs and the next launch starts afresh"
    )]
    RuntimePanicked {
        /// The backend's name.
        backend: &'static str,
        /// The panic's message.
        message: String,
        /// Where the panic happened (`file:line:column`).
        at: String,
    },
    /// A launch its progress callback cancelled.
    #[error(
        "the launch of entry point {entry} was cancelled by its progress callback after {done} of {total} launch indices; its buffers are as they were before it"
    )]
    LaunchCancelled {
        /// The entry point.
        entry: u32,
        /// Launch indices run before the cancel.
        done: u64,
        /// Launch indices of the whole launch.
        total: u64,
    },
    /// A state the runtime should never reach (a bug in rt-runtime),
    /// caught in a launch or a stage's run before it could do harm.
    #[error("the {backend} backend: {problem}")]
    Internal {
        /// The backend's name.
        backend: &'static str,
        /// What is wrong, in a sentence.
        problem: String,
    },
}
