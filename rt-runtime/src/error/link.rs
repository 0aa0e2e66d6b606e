//! Linking: programs set where they do not fit, variables no scope sets
//! or sets to another type, entry points and ray types that do not exist,
//! and programs that disagree on a payload, an attribute or a WGSL item.

use rt_std::program::ProgramKind;

/// Programs and variables that do not link, each error naming the program
/// with its Rust file and line.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LinkError {
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
}
