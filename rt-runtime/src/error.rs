//! Every way a host call, a link or a launch can fail, each naming what is
//! at fault (the program with its Rust file and line, the variable, the
//! scope, the handle).

use rt_std::program::ProgramKind;

/// A runtime error.
#[derive(Debug, thiserror::Error)]
pub enum RtError {
    #[error("`{program}` ({location}) is a {found:?} program, but {slot} takes a {expected:?} program")]
    WrongProgramKind {
        program: &'static str,
        location: String,
        found: ProgramKind,
        expected: ProgramKind,
        slot: String,
    },
    #[error("callable programs call each other in a cycle, which no backend runs (WGSL has no recursion): {cycle}")]
    CallableCycle { cycle: String },
    #[error("`{program}` ({location}) is a callable program of signature `{signature}`, not `{asked}`")]
    CallableSignature { program: &'static str, location: String, signature: &'static str, asked: String },
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to {found}"
    )]
    CallableVariable {
        program: &'static str,
        location: String,
        variable: String,
        declared: String,
        scope: String,
        found: String,
    },
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to {found}"
    )]
    BindlessVariable {
        program: &'static str,
        location: String,
        variable: String,
        declared: String,
        scope: String,
        found: String,
    },
    #[error(
        "variable `{variable}` of {kind:?} program `{program}` ({location}) is set in no scope (searched, innermost first: {searched})"
    )]
    VariableNotFound { program: &'static str, location: String, kind: ProgramKind, variable: String, searched: String },
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to `{found}`"
    )]
    VariableType {
        program: &'static str,
        location: String,
        variable: String,
        declared: String,
        scope: String,
        found: String,
    },
    #[error("ray type {ray_type} has no miss program (set one with `set_miss_program`)")]
    NoMissProgram { ray_type: u32 },
    #[error("entry point {entry} has no ray generation program")]
    NoRayGeneration { entry: u32 },
    #[error("entry point {entry} does not exist: the context has {count} (see `set_entry_point_count`)")]
    NoSuchEntryPoint { entry: u32, count: u32 },
    #[error("ray type {ray_type} does not exist: the context has {count} (see `set_ray_type_count`)")]
    NoSuchRayType { ray_type: u32, count: u32 },
    #[error(
        "payload types disagree on ray type {ray_type}: `{a}` ({a_location}) takes `{a_type}` but `{b}` ({b_location}) takes `{b_type}`"
    )]
    PayloadMismatch {
        ray_type: u32,
        a: &'static str,
        a_location: String,
        a_type: &'static str,
        b: &'static str,
        b_location: String,
        b_type: &'static str,
    },
    #[error("program `{program}` ({location}) traces a `{payload}` payload, but no ray type's programs take one")]
    TracedPayloadUnused { program: &'static str, location: String, payload: &'static str },
    #[error(
        "attribute types disagree: intersection program `{intersection}` ({intersection_location}) reports `{reported}`, but `{hit}` ({hit_location}) takes `{taken}`"
    )]
    AttributeMismatch {
        intersection: &'static str,
        intersection_location: String,
        reported: &'static str,
        hit: &'static str,
        hit_location: String,
        taken: &'static str,
    },
    #[error(
        "programs disagree on WGSL item `{item}`: `{a}` ({a_location}) and `{b}` ({b_location}) define it differently (two types or helpers with one name?)"
    )]
    LinkConflict { item: String, a: &'static str, a_location: String, b: &'static str, b_location: String },
    /// What the device or its driver reported, or a limit of the device
    /// the launch does not fit.
    #[error("the wgpu backend: {0}")]
    Gpu(String),
    /// A setting (an environment variable such as `RT_BACKEND` or
    /// `RT_TRAVERSAL`) of a value the runtime does not know.
    #[error("{setting} is `{value}`; expected {expected}")]
    Config { setting: &'static str, value: String, expected: &'static str },
    /// Something asked for (a backend, a traversal) that this build or
    /// this adapter cannot give, and why.
    #[error("{asked} was asked for, but {why}")]
    Unsupported { asked: &'static str, why: String },
    /// A blocking call where the caller cannot block (a browser page).
    #[error(
        "this call waits for the GPU, which a browser page cannot do in a blocking call: use Context::launch_async"
    )]
    WouldBlock,
    #[error(
        "the wgpu device on {adapter} was lost during the launch ({reason}); the launch wrote none of its outputs and the context's data is unchanged: the next launch opens a new device and uploads the scene again"
    )]
    DeviceLost { adapter: String, reason: String },
    #[error("texture {path}: {problem}")]
    Texture { path: String, problem: String },
    #[error("{0} is not a valid handle of this context")]
    InvalidHandle(String),
    #[error("acceleration builder `{builder}` cannot be honoured: {reason}")]
    UnsupportedBuilder { builder: &'static str, reason: &'static str },
    #[error("geometry {geometry}: {problem}")]
    BadGeometry { geometry: u32, problem: String },
    #[error("transform: {problem}")]
    BadTransform { problem: String },
    #[error("buffer {buffer}: {problem}")]
    BadBuffer { buffer: u32, problem: String },
    #[error("sampler {sampler}: {problem}")]
    BadSampler { sampler: u32, problem: String },
    #[error("launch of {width}x{height}: {problem}")]
    BadLaunch { width: u32, height: u32, problem: String },
    #[error("program `{program}` ({location}) declares {count} variables; at most {max} are supported")]
    TooManyVariables { program: &'static str, location: String, count: usize, max: usize },
    #[error(
        "bounding-box program `{program}` ({location}) gave primitive {primitive} of geometry {geometry} the box {bounds}, with {problem}; a box must be finite with min <= max on every axis"
    )]
    BadBounds {
        program: &'static str,
        location: String,
        geometry: u32,
        primitive: u32,
        bounds: String,
        problem: &'static str,
    },
    #[error("the scene graph has a cycle through node {node}")]
    GraphCycle { node: u32 },
    #[error(
        "node {node}: {count} {what} is more than {adapter} builds (at most {limit}); use the compute traversal (`Traversal::Compute`, RT_TRAVERSAL=compute) or split the scene"
    )]
    AccelerationLimit { node: u32, what: &'static str, count: u64, limit: u64, adapter: String },
    #[error(
        "program `{program}` ({location}) panicked at launch index {launch_index} ({at}): {message}; the launch wrote none of its outputs"
    )]
    ProgramPanicked {
        program: &'static str,
        location: String,
        launch_index: glam::UVec2,
        message: String,
        /// Where the panic happened (`file:line:column`), in the program or
        /// in code it called.
        at: String,
    },
    #[error(
        "bounding-box program `{program}` ({location}) panicked for primitive {primitive} ({at}): {message}; nothing was built"
    )]
    BoundsPanicked { program: &'static str, location: String, primitive: u32, message: String, at: String },
    #[error(
        "the {backend} backend panicked during the launch ({at}): {message}; this is a bug in rt-runtime; the launch wrote none of its outputs and the next launch starts afresh"
    )]
    RuntimePanicked { backend: &'static str, message: String, at: String },
    #[error(
        "the launch of entry point {entry} was cancelled by its progress callback after {done} of {total} launch indices; its buffers are as they were before it"
    )]
    LaunchCancelled { entry: u32, done: u64, total: u64 },
    #[error("writing {path}: {problem}")]
    Image { path: String, problem: String },
    /// A post-processing stage whose variable (a buffer, a setting) is
    /// missing or does not fit: `stage` names the stage (its index and
    /// kind), `variable` the variable at fault.
    #[error("post-processing stage {stage}: variable `{variable}` {problem}")]
    BadStage { stage: String, variable: String, problem: String },
    /// A command list used out of order (appended to after finalizing,
    /// executed before), or one of its commands that does not fit.
    #[error("command list: {problem}")]
    BadCommandList { problem: String },
}

/// Results of the runtime.
pub type Result<T, E = RtError> = std::result::Result<T, E>;
