//! A block: up to `LANES` launch indices run by one call of the ray
//! generation program's lane-wise form (`rt_std::cpu::lanes`), a 4 x 4
//! square of a band of four rows ([`Band`]), so that its camera rays make
//! a packet coherent in both directions (on the bunny, 4x4 blocks of 16
//! cost 7% fewer instructions a pixel than rows of 8, callgrind). The
//! launch's exceptions and prints are put back in launch-index order at
//! its end ([`in_index_order`]).
//!
//! Each launch index of the block has its own execution context, which
//! rt-std switches between with one pointer as the program runs a lane's
//! statements (`lanes::enter_lane`). The lane's own per-index state (its
//! launch index, the first exception of the programs its traces ran, its
//! prints) is kept per block lane ([`Block`]) and loaded lazily: only
//! when a call into the backend comes from another lane than the one loaded
//! ([`Lane::sync_block_lane`], at `rt_trace` and `rt_printf!`), so a run of
//! plain statements pays nothing for it. At the end each launch index is
//! finished as a scalar run finishes it, in index order.

use super::super::LaunchReport;
use super::super::tiles::Tile;
use super::lane::Lane;
use glam::UVec2;
use rt_std::cpu::lanes::{LANES, LaneArgs, LanesEntry, Mask, current_lane, enter_lane, in_block};
use std::sync::atomic::{AtomicBool, Ordering};

/// No block lane's state is loaded into the lane.
const NONE_LOADED: usize = usize::MAX;

/// Rows of a band: blocks are `SIDE` x `SIDE` squares of launch indices
/// (`LANES` of them), so a block's camera rays are a coherent packet in
/// both directions; a band of fewer rows (a 1D launch, the tile's last
/// rows) has blocks as wide as `LANES` allows.
const SIDE: u32 = 4;
const _: () = assert!((SIDE * SIDE) as usize == LANES);

/// Up to `SIDE` rows of a tile (fewer at its end) over a run of its
/// columns, run lane-wise block by block: a chunk of a lane-wise launch.
pub(crate) struct Band {
    /// The band's first launch index.
    origin: UVec2,
    width: u32,
    rows: u32,
}

impl Band {
    /// The tile cut into bands of `SIDE` rows, each cut along its columns
    /// into runs of about `indices` launch indices (whole blocks), so that
    /// a launch of few rows (a 1D launch) still spreads over all cores.
    pub(crate) fn cut(tile: &Tile, indices: u64) -> Vec<Band> {
        let mut bands = Vec::new();
        for y in (0..tile.size.y).step_by(SIDE as usize) {
            let rows = SIDE.min(tile.size.y - y);
            let side = block_width(rows);
            let columns = ((indices / u64::from(rows)) as u32 / side).max(1) * side;
            for x in (0..tile.size.x).step_by(columns as usize) {
                let origin = tile.origin + UVec2::new(x, y);
                bands.push(Band { origin, width: columns.min(tile.size.x - x), rows });
            }
        }
        bands
    }
}

/// The width of a band's blocks of `rows` rows: as many columns as
/// `LANES` fill.
fn block_width(rows: u32) -> u32 {
    (LANES as u32 / rows).max(1)
}

/// A lane-wise launch's exceptions and prints put in launch-index order,
/// as a run one index at a time gives them. (Stable sorts: an index's own
/// exceptions and prints keep their order.)
pub(crate) fn in_index_order(report: &mut LaunchReport) {
    report.exceptions.sort_by_key(|e| (e.launch_index.y, e.launch_index.x));
    report.prints.sort_by_key(|(index, _)| (index.y, index.x));
}

impl Lane<'_> {
    /// Runs `band` block by block through the ray generation program's
    /// lane-wise `entry` (until `stop`), its exceptions and prints into
    /// `report` block by block (the launch puts them in launch-index order
    /// at its end: [`in_index_order`]).
    pub(crate) fn run_band(&self, entry: LanesEntry, band: &Band, report: &mut LaunchReport, stop: &AtomicBool) {
        let side = block_width(band.rows);
        let mut x = 0;
        while x < band.width && !stop.load(Ordering::Relaxed) {
            let w = side.min(band.width - x);
            let mut indices = [UVec2::ZERO; LANES];
            let mut n = 0;
            for y in 0..band.rows {
                for k in 0..w {
                    indices[n] = band.origin + UVec2::new(x + k, y);
                    n += 1;
                }
            }
            self.run_block(entry, &indices[..n], report);
            x += w;
        }
    }

    /// Runs `indices` (at most `LANES`) through the ray generation
    /// program's lane-wise `entry`.
    pub(crate) fn run_block(&self, entry: LanesEntry, indices: &[UVec2], report: &mut LaunchReport) {
        let l = self.l;
        let n = indices.len().min(LANES);
        let mut mask: Mask = [false; LANES];
        self.depth.set(0);
        self.rays.set(0);
        self.time.set(0.0);
        let mut contexts = [self.base; LANES];
        for (i, &index) in indices.iter().enumerate().take(n) {
            self.index.set(index);
            let launch = self.launch_index();
            (contexts[i].launch_index, contexts[i].launch_z) = launch;
            self.block.indices[i].set(index);
            self.block.launches[i].set(launch);
            self.block.exceptions[i].set(None);
            mask[i] = true;
        }
        self.block.loaded.set(NONE_LOADED);
        self.block.active.set(true);
        let rg = &l.ray_generation;
        let outer = self.program.replace(Some(rg.desc));
        in_block(&mut contexts, || entry(&mask, &mut LaneArgs::default(), &rg.vars));
        self.program.set(outer);
        self.store_block_lane();
        self.block.active.set(false);
        report.rays += self.rays.get();
        for (i, ctx) in contexts.iter().enumerate().take(n) {
            let index = self.block.indices[i].get();
            let own = ctx.pending_exception.map(|c| (c, ctx.pending_location));
            self.index.set(index);
            self.launch.set(self.block.launches[i].get());
            self.exception.set(self.block.exceptions[i].get().or(own));
            *self.prints.borrow_mut() = std::mem::take(&mut self.block.prints.borrow_mut()[i]);
            self.finish_index(index, report);
        }
    }

    /// Makes block lane `i` the running one: its execution context current
    /// and its per-index state loaded.
    #[inline]
    pub(crate) fn enter_block_lane(&self, i: usize) {
        enter_lane(i);
        self.sync_block_lane();
    }

    /// Inside a block, loads the per-index state of the lane running now
    /// (`lanes::current_lane`) if another lane's is loaded; outside one,
    /// nothing.
    #[inline]
    pub(crate) fn sync_block_lane(&self) {
        if self.block.active.get() && self.block.loaded.get() != current_lane() {
            self.load_block_lane(current_lane());
        }
    }

    /// Keeps the loaded lane's state, then loads lane `i`'s.
    #[inline(never)]
    fn load_block_lane(&self, i: usize) {
        self.store_block_lane();
        self.index.set(self.block.indices[i].get());
        self.launch.set(self.block.launches[i].get());
        self.exception.set(self.block.exceptions[i].get());
        self.block.loaded.set(i);
    }

    /// Keeps what the loaded lane's programs changed of its state (its
    /// first exception, its prints) in the block; then no lane's is loaded.
    pub(crate) fn store_block_lane(&self) {
        let i = self.block.loaded.replace(NONE_LOADED);
        if i == NONE_LOADED {
            return;
        }
        self.block.exceptions[i].set(self.exception.get());
        if !self.prints.borrow().is_empty() {
            self.block.prints.borrow_mut()[i].append(&mut self.prints.borrow_mut());
        }
    }

    /// The launch index a panic ended: inside a block, the lane's that was
    /// running.
    pub(crate) fn index_at_fault(&self) -> UVec2 {
        match self.block.active.get() {
            true => self.block.indices[current_lane().min(LANES - 1)].get(),
            false => self.index.get(),
        }
    }
}
