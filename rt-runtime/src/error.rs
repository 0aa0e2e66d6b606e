//! Every way a host call, a link or a launch can fail, each naming what is
//! at fault (the program with its Rust file and line, the variable, the
//! scope, the handle).

use rt_std::program::ProgramKind;

/// A runtime error.
#[derive(Debug, thiserror::Error)]
pub enum RtError {
    /// A program set in a slot of another kind.
    #[error("`{program}` ({location}) is a {found:?} program, but {slot} takes a {expected:?} program")]
    WrongProgramKind {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The kind the program is.
        found: ProgramKind,
        /// The kind the slot takes.
        expected: ProgramKind,
        /// The slot it was set to (`ray type 0's miss`).
        slot: String,
    },
    /// Callable programs that call each other in a cycle.
    #[error("callable programs call each other in a cycle, which no backend runs (WGSL has no recursion): {cycle}")]
    CallableCycle {
        /// The programs of the cycle, in call order.
        cycle: String,
    },
    /// A callable program called through a variable of another signature.
    #[error("`{program}` ({location}) is a callable program of signature `{signature}`, not `{asked}`")]
    CallableSignature {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// Its signature.
        signature: &'static str,
        /// The signature the caller's variable declares.
        asked: String,
    },
    /// A callable-program variable set to something else, or to a program of another signature.
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to {found}"
    )]
    CallableVariable {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The variable's name.
        variable: String,
        /// Its type as the program declares it.
        declared: String,
        /// The scope that sets it.
        scope: String,
        /// What the scope sets it to.
        found: String,
    },
    /// A bindless (buffer- or sampler-id) variable set to a value of another type.
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to {found}"
    )]
    BindlessVariable {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The variable's name.
        variable: String,
        /// Its type as the program declares it.
        declared: String,
        /// The scope that sets it.
        scope: String,
        /// What the scope sets it to.
        found: String,
    },
    /// A variable a program declares that no scope it reads sets.
    #[error(
        "variable `{variable}` of {kind:?} program `{program}` ({location}) is set in no scope (searched, innermost first: {searched})"
    )]
    VariableNotFound {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The program's kind.
        kind: ProgramKind,
        /// The variable's name.
        variable: String,
        /// The scopes searched, innermost first.
        searched: String,
    },
    /// A variable set to a value of another type than the program declares.
    #[error(
        "variable `{variable}` of program `{program}` ({location}) is declared `{declared}`, but the {scope} scope sets it to `{found}`"
    )]
    VariableType {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The variable's name.
        variable: String,
        /// Its type as the program declares it.
        declared: String,
        /// The scope that sets it.
        scope: String,
        /// What the scope sets it to.
        found: String,
    },
    /// An entry point launched without a ray-generation program.
    #[error("entry point {entry} has no ray generation program")]
    NoRayGeneration {
        /// The entry point.
        entry: u32,
    },
    /// An entry point beyond the context's count.
    #[error("entry point {entry} does not exist: the context has {count} (see `set_entry_point_count`)")]
    NoSuchEntryPoint {
        /// The entry point asked for.
        entry: u32,
        /// How many entry points the context has.
        count: u32,
    },
    /// A ray type beyond the context's count.
    #[error("ray type {ray_type} does not exist: the context has {count} (see `set_ray_type_count`)")]
    NoSuchRayType {
        /// The ray type asked for.
        ray_type: u32,
        /// How many ray types the context has.
        count: u32,
    },
    /// Two programs of one ray type that take different payload types.
    #[error(
        "payload types disagree on ray type {ray_type}: `{a}` ({a_location}) takes `{a_type}` but `{b}` ({b_location}) takes `{b_type}`"
    )]
    PayloadMismatch {
        /// The ray type.
        ray_type: u32,
        /// The first program's name.
        a: &'static str,
        /// Its Rust file and line.
        a_location: String,
        /// The payload type it takes.
        a_type: &'static str,
        /// The second program's name.
        b: &'static str,
        /// Its Rust file and line.
        b_location: String,
        /// The payload type it takes.
        b_type: &'static str,
    },
    /// A trace with a payload type no ray type's programs take.
    #[error("program `{program}` ({location}) traces a `{payload}` payload, but no ray type's programs take one")]
    TracedPayloadUnused {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// The payload type it traces.
        payload: &'static str,
    },
    /// An intersection program and a hit program that disagree on the attribute type.
    #[error(
        "attribute types disagree: intersection program `{intersection}` ({intersection_location}) reports `{reported}`, but `{hit}` ({hit_location}) takes `{taken}`"
    )]
    AttributeMismatch {
        /// The intersection program's name.
        intersection: &'static str,
        /// Its Rust file and line.
        intersection_location: String,
        /// The attribute type it reports.
        reported: &'static str,
        /// The hit program's name.
        hit: &'static str,
        /// Its Rust file and line.
        hit_location: String,
        /// The attribute type it takes.
        taken: &'static str,
    },
    /// Two programs defining one WGSL item differently.
    #[error(
        "programs disagree on WGSL item `{item}`: `{a}` ({a_location}) and `{b}` ({b_location}) define it differently (two types or helpers with one name?)"
    )]
    LinkConflict {
        /// The WGSL item's name.
        item: String,
        /// The first program's name.
        a: &'static str,
        /// Its Rust file and line.
        a_location: String,
        /// The second program's name.
        b: &'static str,
        /// Its Rust file and line.
        b_location: String,
    },
    /// What the device or its driver reported, or a limit of the device
    /// the launch does not fit.
    #[error("the wgpu backend: {0}")]
    Gpu(String),
    /// A setting (an environment variable such as `RT_BACKEND` or
    /// `RT_TRAVERSAL`) of a value the runtime does not know.
    #[error("{setting} is `{value}`; expected {expected}")]
    Config {
        /// The setting (`RT_BACKEND`).
        setting: &'static str,
        /// The value it has.
        value: String,
        /// The values it may have.
        expected: &'static str,
    },
    /// Something asked for (a backend, a traversal) that this build or
    /// this adapter cannot give, and why.
    #[error("{asked} was asked for, but {why}")]
    Unsupported {
        /// What was asked for.
        asked: &'static str,
        /// Why it cannot be given.
        why: String,
    },
    /// A blocking call where the caller cannot block (a browser page).
    #[error(
        "this call waits for the GPU, which a browser page cannot do in a blocking call: use Context::launch_async"
    )]
    WouldBlock,
    /// The wgpu device was lost during a launch.
    #[error(
        "the wgpu device on {adapter} was lost during the launch ({reason}); the launch wrote none of its outputs and the context's data is unchanged: the next launch opens a new device and uploads the scene again"
    )]
    DeviceLost {
        /// The adapter's name.
        adapter: String,
        /// The reason wgpu gave.
        reason: String,
    },
    /// A texture that could not be read or used.
    #[error("texture {path}: {problem}")]
    Texture {
        /// The texture's file.
        path: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A handle (the `Debug` spelling given) that is not of this context.
    #[error("{0} is not a valid handle of this context")]
    InvalidHandle(String),
    /// An acceleration builder that cannot be honoured.
    #[error("acceleration builder `{builder}` cannot be honoured: {reason}")]
    UnsupportedBuilder {
        /// The builder's name.
        builder: &'static str,
        /// Why it cannot be built.
        reason: &'static str,
    },
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
    /// A program declaring more variables than the runtime supports.
    #[error("program `{program}` ({location}) declares {count} variables; at most {max} are supported")]
    TooManyVariables {
        /// The program's name.
        program: &'static str,
        /// The program's Rust file and line.
        location: String,
        /// How many variables it declares.
        count: usize,
        /// The most a program may declare.
        max: usize,
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
    /// A scene graph with a cycle.
    #[error("the scene graph has a cycle through node {node}")]
    GraphCycle {
        /// A node on the cycle.
        node: u32,
    },
    /// A node larger than the adapter's ray-query acceleration structures hold.
    #[error(
        "node {node}: {count} {what} is more than {adapter} builds (at most {limit}); use the compute traversal (`Traversal::Compute`, RT_TRAVERSAL=compute) or split the scene"
    )]
    AccelerationLimit {
        /// The node, by index.
        node: u32,
        /// What is counted (`TLAS instances (paths down to geometry groups)`).
        what: &'static str,
        /// How many the node has.
        count: u64,
        /// The most the adapter builds.
        limit: u64,
        /// The adapter's name.
        adapter: String,
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
    /// An image that could not be written.
    #[error("writing {path}: {problem}")]
    Image {
        /// The image file.
        path: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A post-processing stage whose variable (a buffer, a setting) is
    /// missing or does not fit: `stage` names the stage (its index and
    /// kind), `variable` the variable at fault.
    #[error("post-processing stage {stage}: variable `{variable}` {problem}")]
    BadStage {
        /// The stage: its index and kind.
        stage: String,
        /// The variable at fault.
        variable: String,
        /// What is wrong, in a sentence.
        problem: String,
    },
    /// A command list used out of order (appended to after finalizing,
    /// executed before), or one of its commands that does not fit.
    #[error("command list: {problem}")]
    BadCommandList {
        /// What is wrong, in a sentence.
        problem: String,
    },
}

/// Results of the runtime.
pub type Result<T, E = RtError> = std::result::Result<T, E>;
