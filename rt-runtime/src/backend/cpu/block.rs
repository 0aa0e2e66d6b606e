//! A block: up to `LANES` launch indices run by one call of the ray
//! generation program's lane-wise form (`rt_std::cpu::lanes`). The lane
//! keeps each launch index's state (its launch index, first exception,
//! pending exception, prints) in [`BlockLane`]s and switches to one around
//! each of its statements (`enter_lane`, `leave_lane`), so every intrinsic
//! and every program the statement reaches sees that launch index, as in
//! the scalar run. At the end each launch index is finished as a scalar
//! run finishes it, in index order.

use super::super::LaunchReport;
use super::lane::{BlockLane, Lane};
use glam::UVec2;
use rt_std::cpu::lanes::{LANES, LaneContext, LanesEntry, Mask};

impl Lane<'_> {
    /// Runs `indices` (at most `LANES`) through the ray generation
    /// program's lane-wise `entry`.
    pub(crate) fn run_block(&self, entry: LanesEntry, indices: &[UVec2], report: &mut LaunchReport) {
        let l = self.l;
        let mut mask: Mask = [false; LANES];
        for (i, &index) in indices.iter().enumerate().take(LANES) {
            self.index.set(index);
            let (launch_index, launch_z) = self.launch_index();
            let context = LaneContext { launch_index, launch_z, ..LaneContext::default() };
            self.block.lanes[i].set(BlockLane { index, context, exception: None });
            mask[i] = true;
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
            let b = self.block.lanes[i].get();
            let own = b.context.pending_exception.map(|c| (c, b.context.pending_location));
            self.index.set(b.index);
            self.launch.set((b.context.launch_index, b.context.launch_z));
            self.exception.set(b.exception.or(own));
            *self.prints.borrow_mut() = std::mem::take(&mut self.block.prints.borrow_mut()[i]);
            self.finish_index(b.index, report);
        }
    }

    /// Switches the lane's per-index state to lane `i` of the block.
    #[inline]
    pub(crate) fn enter_block_lane(&self, i: usize) {
        let b = self.block.lanes[i].get();
        self.index.set(b.index);
        self.launch.set((b.context.launch_index, b.context.launch_z));
        self.exception.set(b.exception);
        rt_std::cpu::lanes::put_lane_context(&b.context);
    }

    /// Keeps what lane `i`'s statement changed of its state.
    #[inline]
    pub(crate) fn leave_block_lane(&self, i: usize) {
        let mut b = self.block.lanes[i].get();
        b.exception = self.exception.get();
        rt_std::cpu::lanes::take_lane_exception(&mut b.context);
        self.block.lanes[i].set(b);
        let mut prints = self.prints.borrow_mut();
        if !prints.is_empty() {
            self.block.prints.borrow_mut()[i].append(&mut prints);
        }
    }
}
