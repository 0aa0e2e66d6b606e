//! Every way a host call, a link or a launch can fail, each naming what is
//! at fault (the program with its Rust file and line, the variable, the
//! scope, the handle).
//!
//! Errors are grouped by concern, a file and an enum each, and
//! [`RtError`] wraps the group: match the group to handle a kind of
//! failure, or the variant inside it for one failure. A group converts
//! into [`RtError`] with `?` or `.into()`; [`RtError`]'s message is its
//! group's, word for word, and so is its `source()`.
//!
//! ```
//! use rt_runtime::error::{LaunchError, RtError, SceneError};
//!
//! fn advice(e: &RtError) -> &'static str {
//!     match e {
//!         RtError::Scene(SceneError::BadSampler { .. }) => "check the sampler's texels",
//!         RtError::Scene(_) => "check the scene",
//!         RtError::Launch(LaunchError::LaunchCancelled { .. }) => "cancelled: nothing was written",
//!         _ => "see the message",
//!     }
//! }
//! let e: RtError = SceneError::GraphCycle { node: 3 }.into();
//! assert_eq!(e.to_string(), "the scene graph has a cycle through node 3");
//! assert_eq!(advice(&e), "check the scene");
//! ```
//!
//! Each variant and the path that matches it:
//!
//! | variant | matched as |
//! |---|---|
//! | `Setting` | `RtError::Config(ConfigError::Setting { .. })` |
//! | `Unsupported` | `RtError::Config(ConfigError::Unsupported { .. })` |
//! | `InvalidHandle` | `RtError::Scene(SceneError::InvalidHandle(_))` |
//! | `BadGeometry` | `RtError::Scene(SceneError::BadGeometry { .. })` |
//! | `BadTransform` | `RtError::Scene(SceneError::BadTransform { .. })` |
//! | `BadBuffer` | `RtError::Scene(SceneError::BadBuffer { .. })` |
//! | `BadSampler` | `RtError::Scene(SceneError::BadSampler { .. })` |
//! | `GraphCycle` | `RtError::Scene(SceneError::GraphCycle { .. })` |
//! | `UnsupportedBuilder` | `RtError::Scene(SceneError::UnsupportedBuilder { .. })` |
//! | `BadBounds` | `RtError::Scene(SceneError::BadBounds { .. })` |
//! | `WrongProgramKind` | `RtError::Link(LinkError::WrongProgramKind { .. })` |
//! | `CallableCycle` | `RtError::Link(LinkError::CallableCycle { .. })` |
//! | `CallableSignature` | `RtError::Link(LinkError::CallableSignature { .. })` |
//! | `CallableVariable` | `RtError::Link(LinkError::CallableVariable { .. })` |
//! | `BindlessVariable` | `RtError::Link(LinkError::BindlessVariable { .. })` |
//! | `VariableNotFound` | `RtError::Link(LinkError::VariableNotFound { .. })` |
//! | `VariableType` | `RtError::Link(LinkError::VariableType { .. })` |
//! | `NoRayGeneration` | `RtError::Link(LinkError::NoRayGeneration { .. })` |
//! | `NoSuchEntryPoint` | `RtError::Link(LinkError::NoSuchEntryPoint { .. })` |
//! | `NoSuchRayType` | `RtError::Link(LinkError::NoSuchRayType { .. })` |
//! | `PayloadMismatch` | `RtError::Link(LinkError::PayloadMismatch { .. })` |
//! | `TracedPayloadUnused` | `RtError::Link(LinkError::TracedPayloadUnused { .. })` |
//! | `AttributeMismatch` | `RtError::Link(LinkError::AttributeMismatch { .. })` |
//! | `LinkConflict` | `RtError::Link(LinkError::LinkConflict { .. })` |
//! | `TooManyVariables` | `RtError::Link(LinkError::TooManyVariables { .. })` |
//! | `Gpu` | `RtError::Device(DeviceError::Gpu(_))` |
//! | `BindingLimit` | `RtError::Device(DeviceError::BindingLimit { .. })` |
//! | `DeviceLost` | `RtError::Device(DeviceError::DeviceLost { .. })` |
//! | `WouldBlock` | `RtError::Device(DeviceError::WouldBlock)` |
//! | `AccelerationLimit` | `RtError::Device(DeviceError::AccelerationLimit { .. })` |
//! | `BadLaunch` | `RtError::Launch(LaunchError::BadLaunch { .. })` |
//! | `ProgramPanicked` | `RtError::Launch(LaunchError::ProgramPanicked { .. })` |
//! | `BoundsPanicked` | `RtError::Launch(LaunchError::BoundsPanicked { .. })` |
//! | `RuntimePanicked` | `RtError::Launch(LaunchError::RuntimePanicked { .. })` |
//! | `LaunchCancelled` | `RtError::Launch(LaunchError::LaunchCancelled { .. })` |
//! | `Internal` | `RtError::Launch(LaunchError::Internal { .. })` |
//! | `Texture` | `RtError::Io(IoError::Texture { .. })` |
//! | `Image` | `RtError::Io(IoError::Image { .. })` |
//! | `BadStage` | `RtError::PostProcess(PostProcessError::BadStage { .. })` |
//! | `BadCommandList` | `RtError::PostProcess(PostProcessError::BadCommandList { .. })` |
//!
//! `RtError` and its groups are `#[non_exhaustive]`: a match outside this
//! crate ends with `_`.

mod config;
mod device;
mod io;
mod launch;
mod link;
mod postprocess;
mod scene;

pub use config::ConfigError;
pub use device::DeviceError;
pub(crate) use device::size;
pub use io::IoError;
pub use launch::LaunchError;
pub use link::LinkError;
pub use postprocess::PostProcessError;
pub use scene::SceneError;

/// A runtime error: its group, and in it the failure.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RtError {
    /// A setting, or something this build or adapter cannot give.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// An object of the scene, or a handle to one.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Programs and variables that do not link.
    #[error(transparent)]
    Link(#[from] LinkError),
    /// What the device reports, or a limit of it.
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// A launch that could not run or did not finish.
    #[error(transparent)]
    Launch(#[from] LaunchError),
    /// A file read or written.
    #[error(transparent)]
    Io(#[from] IoError),
    /// A post-processing stage or a command list.
    #[error(transparent)]
    PostProcess(#[from] PostProcessError),
}

/// Results of the runtime.
pub type Result<T, E = RtError> = std::result::Result<T, E>;
