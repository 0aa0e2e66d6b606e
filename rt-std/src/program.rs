//! Descriptors the `#[rt_program]` macro emits beside each program.
//!
//! This module is the contract between the compiler (`rt-compiler`, run at
//! `cargo build` time) and the runtime: everything the linker needs to know
//! about a program is here, as `'static` data.

use crate::cpu::{CpuArgs, CpuResult};
#[doc(inline)]
pub use crate::layout::{
    CallableSignature, FieldLayout, LayoutKind, SamplerKind, ScalarKind, TriangleBuiltin, TypeLayout,
};

/// The nine kinds of ray program, as in OptiX: the contract's
/// [`rt_abi::Kind`], whose `name()` is the `#[rt_program(...)]` spelling.
pub use rt_abi::Kind as ProgramKind;

/// What a `#[var]` parameter holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VariableKind {
    /// A plain value (scalar, vector, matrix, `#[rt_struct]`).
    Value,
    /// A buffer handle.
    Buffer {
        /// Element type.
        element: TypeLayout,
        /// 1 or 2.
        dimensions: u32,
        /// Whether programs may write it.
        writable: bool,
    },
    /// A 2D texture sampler handle.
    Sampler,
    /// A 3D texture sampler handle.
    Sampler3d,
    /// A cube map sampler handle.
    SamplerCube,
    /// A node of the scene graph to trace against.
    Object,
}

/// A variable a program reads (a `#[var]` parameter).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VariableDescriptor {
    /// The variable's name (the parameter name).
    pub name: &'static str,
    /// Its type as declared.
    pub ty: TypeLayout,
    /// What kind of thing it is.
    pub kind: VariableKind,
    /// The WGSL function that reads the variable from heap words
    /// (`rt_load_vec3f(w: u32) -> vec3<f32>`); the linker calls it to pass
    /// variables from a scope record to the program.
    pub wgsl_load: &'static str,
}

/// A named WGSL item (struct or function) that programs may share; the
/// linker deduplicates them by name and rejects two different texts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WgslItem {
    /// The WGSL name.
    pub name: &'static str,
    /// Its full WGSL text.
    pub text: &'static str,
    /// The names in `text` that per-depth clones rename (see [`WgslSite`]);
    /// empty for types and resumable forms.
    pub sites: &'static [WgslSite],
}

/// A name in a WGSL function's text that the linker may suffix, recorded
/// by the compiler where it lowered the name: where the name ends (a byte
/// offset into the text) and what it names. Per-depth clones suffix a
/// function's own name, its trace and helper calls with `_d<k>`; a
/// callable that calls callables gets dispatch functions of its own, so
/// its calls through ids (and its helpers' that make them) are suffixed
/// with its name. Recorded for the plain forms of programs and helpers, in
/// text order, so the linker renames by offset and never searches the
/// text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WgslSite {
    /// Byte offset in the function's text just past the name.
    pub end: u32,
    /// What the name is.
    pub name: WgslName,
}

/// What a [`WgslSite`] names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WgslName {
    /// The function's own name, in its definition (`fn <name>(`).
    Definition,
    /// A trace call, `rt_trace_<payload>(`: the payload type's WGSL name.
    Trace(&'static str),
    /// A call of the helper of this WGSL name (`rtf_<helper>(`).
    Call(&'static str),
    /// A call through a callable id, `rt_call_<signature>(`: the
    /// signature's dispatch function ([`CallableSignature::dispatch`]).
    Dispatch(&'static str),
}

impl WgslSite {
    /// The trace call sites among `sites`, per payload type (its WGSL
    /// name), in name order.
    pub fn traces_per_payload(sites: &[WgslSite]) -> Vec<(&'static str, usize)> {
        let mut per: std::collections::BTreeMap<&'static str, usize> = Default::default();
        for s in sites {
            if let WgslName::Trace(p) = s.name {
                *per.entry(p).or_default() += 1;
            }
        }
        per.into_iter().collect()
    }

    /// The helpers (WGSL names) `sites` call, each once, in name order.
    pub fn helpers_called(sites: &[WgslSite]) -> Vec<&'static str> {
        let called: std::collections::BTreeSet<&'static str> =
            sites.iter().filter_map(|s| if let WgslName::Call(h) = s.name { Some(h) } else { None }).collect();
        called.into_iter().collect()
    }
}

/// What a callable program's descriptor adds.
#[derive(Clone, Copy, Debug)]
pub struct CallableDescriptor {
    /// Its signature.
    pub signature: CallableSignature,
    /// The Rust function, a `fn(A, ..) -> R` behind `Any` (the CPU
    /// backend's call; the host checks a requested signature against it).
    pub cpu: &'static (dyn core::any::Any + Send + Sync),
}

/// A format string of an `rt_printf!` call, with the types of its arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrintfFormat {
    /// The id the WGSL passes to `rt_printf_begin` (a hash of the format and
    /// argument types, so shared helpers print the same id everywhere).
    pub id: u32,
    /// The format string as written (`{}` placeholders).
    pub format: &'static str,
    /// WGSL types of the arguments in order (`f32`, `vec3<f32>`, ...).
    pub args: &'static [&'static str],
}

/// Binds variable values to a program's parameter types (CPU backend).
pub type CpuBind = for<'a> fn(
    &[&'a (dyn core::any::Any + Send + Sync)],
) -> Result<crate::cpu::BoundVariables<'a>, crate::cpu::VariableMismatch>;

/// Makes a program's attribute value from heap words (CPU backend).
pub type AttributesFromWords = fn(&[u32]) -> Box<dyn crate::cpu::AnyAttributes>;

/// Everything known about one program after `cargo build`.
#[derive(Clone, Copy, Debug)]
pub struct ProgramDescriptor {
    /// Program kind.
    pub kind: ProgramKind,
    /// Rust function name.
    pub name: &'static str,
    /// Name of the program's function in WGSL (`rtp_<name>`).
    pub wgsl_entry: &'static str,
    /// The whole standalone WGSL module that naga validated at build time:
    /// a prelude of runtime stubs, the types, helpers and the program.
    pub wgsl: &'static str,
    /// The prelude of runtime stubs alone (the linker replaces it).
    pub wgsl_prelude: &'static str,
    /// Struct types the program uses, in dependency order.
    pub wgsl_types: &'static [WgslItem],
    /// Helper functions (`#[rt_function]`s and generated accessors), in
    /// dependency order.
    pub wgsl_functions: &'static [WgslItem],
    /// The program function itself.
    pub wgsl_program: &'static str,
    /// The names in `wgsl_program` that per-depth clones rename: its own,
    /// its trace calls and its helper calls (see [`WgslSite`]).
    pub wgsl_program_sites: &'static [WgslSite],
    /// For programs that trace: the resumable form (per-depth frame arrays
    /// and the same function, which returns to the kernel at each trace and
    /// is called again to resume), when the compiler could make one. The
    /// linker runs such programs from one loop, so no code is cloned per
    /// trace depth.
    pub wgsl_resumable: Option<&'static str>,
    /// The resumable forms (`<helper>_rs`) of the helpers that trace which
    /// the resumable form calls.
    pub wgsl_resumable_functions: &'static [WgslItem],
    /// For programs that trace but have no resumable form: why not (the
    /// construct the compiler could not suspend in).
    pub not_resumable: Option<&'static str>,
    /// Payload type, for programs that take one.
    pub payload: Option<TypeLayout>,
    /// Attribute type, for programs that take one.
    pub attributes: Option<TypeLayout>,
    /// Variables in parameter order (the WGSL function takes them in this
    /// order after payload/attributes/primitive index).
    pub variables: &'static [VariableDescriptor],
    /// Intrinsics the program calls, directly or through helpers.
    pub intrinsics: &'static [&'static str],
    /// Payload types passed to `rt_trace`.
    pub traced_payloads: &'static [TypeLayout],
    /// `rt_printf!` formats the program (and its helpers) use.
    pub printf: &'static [PrintfFormat],
    /// The signatures of the callables the program (and its helpers) call.
    pub calls: &'static [CallableSignature],
    /// For callable programs: the signature and the Rust function.
    pub callable: Option<CallableDescriptor>,
    /// Rust source file of the program.
    pub file: &'static str,
    /// Line of the program's `fn` in that file.
    pub line: u32,
    /// The program compiled as Rust, for the CPU backend.
    pub cpu: fn(&mut CpuArgs<'_>) -> CpuResult,
    /// Binds variable values (in [`variables`](Self::variables) order) to
    /// the program's parameter types, checking each once: the
    /// [`CpuArgs::variables`] that [`cpu`](Self::cpu) takes.
    pub cpu_bind: CpuBind,
    /// For programs taking attributes: makes a value of the attribute type
    /// from heap words (the CPU backend fills built-in triangle attributes
    /// this way).
    pub cpu_attributes: Option<AttributesFromWords>,
    /// The program compiled lane-wise for the CPU backend, or why it runs
    /// one launch index at a time there.
    pub cpu_lanes: CpuLanes,
}

/// Whether the CPU backend can run a program lane-wise
/// ([`crate::cpu::lanes`]).
#[derive(Clone, Copy, Debug)]
pub enum CpuLanes {
    /// The program's lane-wise entry.
    Lanes(crate::cpu::lanes::LanesEntry),
    /// The program runs one launch index at a time: the construct, or the
    /// kind of program, the lane-wise lowering does not take.
    Scalar(&'static str),
}

impl ProgramDescriptor {
    /// `file:line` of the program, for error messages.
    pub fn location(&self) -> String {
        format!("{}:{}", self.file, self.line)
    }
}

impl PartialEq for ProgramDescriptor {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
            && self.kind == other.kind
            && self.file == other.file
            && self.line == other.line
            && self.wgsl == other.wgsl
    }
}
