//! The shape of a lane-wise block, below everything that runs one: how
//! many launch indices it holds, which of them run, and each one's own part
//! of the execution context. [`super::lanes`] runs blocks; the
//! [`Tracer`](super::Tracer) takes their masks.

/// The number of launch indices a lane-wise program runs at once.
pub const LANES: usize = 8;

/// Which lanes run: `true` for a running lane.
pub type Mask = [bool; LANES];

/// A program's lane-wise entry: runs the lanes of `mask` (the backend has
/// set up each lane's launch index) with the program's variables.
pub type LanesEntry = fn(&Mask, &super::thunk::BoundVariables<'_>);

/// A lane's own part of this thread's execution context: its launch index
/// and slice, and the exception its program raised and where.
#[derive(Clone, Copy, Debug, Default)]
pub struct LaneContext {
    /// [`launch_index`](crate::launch_index) in the lane.
    pub launch_index: glam::UVec2,
    /// The slice of a 3D launch.
    pub launch_z: u32,
    /// The exception the lane's program raised, if any.
    pub pending_exception: Option<u32>,
    /// Where, when the raiser said.
    pub pending_location: Option<&'static core::panic::Location<'static>>,
}
