//! The shape of a lane-wise block, below everything that runs one: how
//! many launch indices it holds, which of them run, and the entry that runs
//! them. [`super::lanes`] runs blocks; the [`Tracer`](super::Tracer) takes
//! their masks.

/// The number of launch indices a lane-wise program runs at once: the
/// CPU backend's blocks are 4 x 4 squares of them, whose camera rays make
/// a coherent packet (`rt-runtime/src/backend/cpu/block.rs`).
pub const LANES: usize = 16;

/// Which lanes run: `true` for a running lane.
pub type Mask = [bool; LANES];

/// A program's lane-wise entry: runs the lanes of `mask` (the backend has
/// given each lane its execution context, [`in_block`](super::lanes::in_block))
/// with their payloads and attributes and the program's variables.
pub type LanesEntry = fn(&Mask, &mut LaneArgs<'_>, &super::thunk::BoundVariables<'_>);

/// What a hit or miss program's lanes take, lane by lane: the payload
/// (`&mut P`) and the attributes (`&A`), as [`CpuArgs`](super::CpuArgs)
/// holds them for one call. A ray generation program takes neither.
#[derive(Default)]
pub struct LaneArgs<'a> {
    /// Each lane's payload.
    pub payloads: [Option<&'a mut dyn core::any::Any>; LANES],
    /// Each lane's attributes.
    pub attributes: [Option<&'a mut dyn core::any::Any>; LANES],
}
