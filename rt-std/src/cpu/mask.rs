//! The shape of a lane-wise block, below everything that runs one: how
//! many launch indices it holds, which of them run, and the entry that runs
//! them. [`super::lanes`] runs blocks; the [`Tracer`](super::Tracer) takes
//! their masks.

/// The number of launch indices a lane-wise program runs at once.
pub const LANES: usize = 8;

/// Which lanes run: `true` for a running lane.
pub type Mask = [bool; LANES];

/// A program's lane-wise entry: runs the lanes of `mask` (the backend has
/// given each lane its execution context, [`in_block`](super::lanes::in_block))
/// with the program's variables.
pub type LanesEntry = fn(&Mask, &super::thunk::BoundVariables<'_>);
