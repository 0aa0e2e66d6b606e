//! A block: up to `LANES` launch indices run by one call of the ray
//! generation program's lane-wise form (`rt_std::cpu::lanes`). The lane
//! keeps each launch index's state (its launch index, first exception,
//! pending exception, prints) in [`BlockLane`]s and switches to one around
//! each of its statements (`enter_lane`, `leave_lane`), so every intrinsic
//! and every program the statement reaches sees that launch index, as in
//! the scalar run. At the end each launch index is finished as a scalar
//! run finishes it, in index order.

use super::super::LaunchReport;
use super::lane::Lane;
use glam::UVec2;
use rt_std::cpu::lanes::{LANES, LaneContext, LanesEntry, Mask};

/// One launch index of the running block.
#[derive(Clone, Debug, Default)]
pub(crate) struct BlockLane {
    /// The grid index (what reports name).
    index: UVec2,
    /// The launch index and slice, and the program's pending exception.
    context: LaneContext,
    /// The first exception of a program the lane's traces ran.
    exception: Option<(u32, Option<&'static std::panic::Location<'static>>)>,
    prints: Vec<String>,
}

impl Lane<'_> {
    /// Runs `indices` (at most `LANES`) through the ray generation
    /// program's lane-wise `entry`.
    pub(crate) fn run_block(&self, entry: LanesEntry, indices: &[UVec2], report: &mut LaunchReport) {
        let l = self.l;
        let mut mask: Mask = [false; LANES];
        {
            let mut block = self.block.borrow_mut();
            for (i, &index) in indices.iter().enumerate().take(LANES) {
                self.index.set(index);
                let (launch_index, launch_z) = self.launch_index();
                block[i] = BlockLane {
                    index,
                    context: LaneContext { launch_index, launch_z, ..LaneContext::default() },
                    exception: None,
                    prints: Vec::new(),
                };
                mask[i] = true;
            }
        }
        self.depth.set(0);
        self.rays.set(0);
        self.time.set(0.0);
        let rg = &l.ray_generation;
        let mut ctx = self.context();
        let outer = self.program.replace(Some(rg.desc));
        rt_std::cpu::in_context(&mut ctx, || entry(&mask, &rg.vars));
        self.program.set(outer);
        report.rays += self.rays.get();
        for i in 0..indices.len().min(LANES) {
            let (index, launch, exception, prints) = {
                let mut block = self.block.borrow_mut();
                let b = &mut block[i];
                let own = b.context.pending_exception.map(|c| (c, b.context.pending_location));
                let launch = (b.context.launch_index, b.context.launch_z);
                (b.index, launch, b.exception.or(own), std::mem::take(&mut b.prints))
            };
            self.index.set(index);
            self.launch.set(launch);
            self.exception.set(exception);
            *self.prints.borrow_mut() = prints;
            self.finish_index(index, report);
        }
    }

    /// Switches the lane's per-index state to lane `i` of the block.
    pub(crate) fn enter_block_lane(&self, i: usize) {
        let block = self.block.borrow();
        let b = &block[i];
        self.index.set(b.index);
        self.launch.set((b.context.launch_index, b.context.launch_z));
        self.exception.set(b.exception);
        rt_std::cpu::lanes::put_lane_context(&b.context);
    }

    /// Keeps what lane `i`'s statement changed of its state.
    pub(crate) fn leave_block_lane(&self, i: usize) {
        let mut block = self.block.borrow_mut();
        let b = &mut block[i];
        b.exception = self.exception.get();
        rt_std::cpu::lanes::take_lane_exception(&mut b.context);
        let mut prints = self.prints.borrow_mut();
        if !prints.is_empty() {
            b.prints.append(&mut prints);
        }
    }
}
