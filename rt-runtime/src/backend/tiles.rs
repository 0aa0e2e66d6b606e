//! Tiles: a launch cut into pieces that each stay under a time budget.
//!
//! Desktop drivers reset a GPU whose work runs past about two seconds
//! (Windows' TDR, Linux's hang check), and a user waiting on a long render
//! wants to see it advance and to stop it. So a launch runs as tiles, one
//! submission each: `Tiler` cuts the launch into whole 8 x 8 blocks (the
//! megakernel's workgroups) in row-major order, either bands of whole rows
//! or pieces of one band of at most 8 rows; `Pace` remembers how long an
//! index of each entry point took, so the next tile is sized to half the
//! budget. Every launch index runs exactly once, whatever the cut, and the
//! outputs, exceptions and prints are those of one launch over the whole
//! size (`tests/tests/tiled_launches.rs`).
//!
//! Between tiles the context reports [`LaunchProgress`] to a callback,
//! which may cancel ([`LaunchControl::Cancel`]): the launch then fails with
//! [`LaunchError::LaunchCancelled`](crate::LaunchError::LaunchCancelled) and the
//! buffers are left as they were before it.

use glam::UVec2;
use std::collections::HashMap;
use std::time::Duration;

/// How a context cuts its launches into tiles
/// ([`Context::set_tile_budget`](crate::Context::set_tile_budget)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileBudget {
    /// Tiles sized so that each runs in about half this time, from the
    /// time earlier tiles of the same entry point took (the first tile of
    /// an entry point is a probe of [`PROBE_INDICES`] indices). The
    /// default is [`DEFAULT_TILE_BUDGET`].
    Time(Duration),
    /// Tiles of at most this many launch indices (rounded down to whole
    /// 8 x 8 blocks, at least one): the same cut on every machine.
    Indices(u64),
    /// One tile: the whole launch in one submission, as before tiles.
    Whole,
}

impl Default for TileBudget {
    fn default() -> Self {
        TileBudget::Time(DEFAULT_TILE_BUDGET)
    }
}

/// The default time budget of a tile: a quarter of the two seconds after
/// which desktop drivers reset a GPU (tiles are sized to half of it).
pub const DEFAULT_TILE_BUDGET: Duration = Duration::from_millis(500);

/// The launch indices of an entry point's first timed tile, before its pace
/// is known: small enough for any device to run well inside the budget.
pub const PROBE_INDICES: u64 = 1 << 16;

/// How fast a tile may grow over the last one: a pace measured on a small
/// tile may be off (caches, a cold pipeline).
const MAX_GROWTH: u64 = 4;

/// Where a launch stands, reported between its tiles
/// ([`Context::launch_with_progress`](crate::Context::launch_with_progress)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaunchProgress {
    /// The entry point launched.
    pub entry: u32,
    /// Launch indices run so far.
    pub done: u64,
    /// Launch indices in all.
    pub total: u64,
    /// Tiles run so far.
    pub tiles: u32,
    /// Time since the launch began.
    pub elapsed: Duration,
}

impl LaunchProgress {
    /// `done / total`, from 0 to 1.
    pub fn fraction(&self) -> f64 {
        if self.total == 0 { 1.0 } else { self.done as f64 / self.total as f64 }
    }
}

/// What a progress callback answers: go on with the next tile, or stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LaunchControl {
    /// Go on with the next tile.
    Continue,
    /// Stop before the next tile: the launch fails with
    /// [`LaunchError::LaunchCancelled`](crate::LaunchError::LaunchCancelled) and
    /// leaves the buffers as they were.
    Cancel,
}

/// A rectangle of launch indices: `origin` and `size`, the origin on the
/// 8 x 8 block grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    /// The first launch index of the tile.
    pub origin: UVec2,
    /// Its width and height in launch indices.
    pub size: UVec2,
}

impl Tile {
    /// The whole launch of `width` x `height`.
    pub fn whole(width: u32, height: u32) -> Tile {
        Tile { origin: UVec2::ZERO, size: UVec2::new(width, height) }
    }

    /// Launch indices in the tile.
    pub fn count(&self) -> u64 {
        self.size.x as u64 * self.size.y as u64
    }

    /// The tile's `i`-th launch index, in row-major order.
    pub fn index(&self, i: u64) -> UVec2 {
        let w = self.size.x as u64;
        self.origin + UVec2::new((i % w) as u32, (i / w) as u32)
    }
}

/// Side of the square blocks a launch is cut along.
const BLOCK: u32 = 8;

/// Cuts a launch (or a part of it on the block grid) into tiles of whole
/// blocks, in row-major order of blocks: a tile of at least a band's
/// blocks is whole bands (rows of blocks), a smaller one is a run of blocks
/// along one band.
#[derive(Clone, Debug)]
pub(crate) struct Tiler {
    /// What is cut: its origin on the block grid.
    part: Tile,
    /// The next block, in block units from the part's origin.
    next: UVec2,
}

impl Tiler {
    /// Cuts `part`, whose origin is on the block grid.
    pub fn new(part: Tile) -> Tiler {
        debug_assert_eq!(part.origin % BLOCK, UVec2::ZERO);
        Tiler { part, next: UVec2::ZERO }
    }

    fn blocks(&self) -> UVec2 {
        UVec2::new(self.part.size.x.div_ceil(BLOCK), self.part.size.y.div_ceil(BLOCK))
    }

    /// Whether every index has been handed out.
    pub fn finished(&self) -> bool {
        self.next.y >= self.blocks().y
    }

    /// The next tile, of about `indices` launch indices (at least one
    /// block; whole bands when it reaches a band's width from the band's
    /// start), or `None` once all are out.
    pub fn next_tile(&mut self, indices: u64) -> Option<Tile> {
        if self.finished() {
            return None;
        }
        let (blocks, size) = (self.blocks(), self.part.size);
        // The indices a block holds on this band (fewer on the last band of
        // a part whose height is not a multiple of 8, or a 1D launch).
        let band_rows = (size.y - self.next.y * BLOCK).min(BLOCK);
        let per_block = (BLOCK * band_rows) as u64;
        let want = (indices / per_block).max(1);
        let at = self.next * BLOCK;
        let origin = self.part.origin + at;
        if self.next.x == 0 && want >= blocks.x as u64 {
            let bands = (indices / (blocks.x as u64 * (BLOCK * BLOCK) as u64)).max(1);
            let bands = bands.min((blocks.y - self.next.y) as u64) as u32;
            self.next.y += bands;
            let rows = (bands * BLOCK).min(size.y - at.y);
            return Some(Tile { origin, size: UVec2::new(size.x, rows) });
        }
        let run = want.min((blocks.x - self.next.x) as u64) as u32;
        self.next.x += run;
        if self.next.x == blocks.x {
            self.next = UVec2::new(0, self.next.y + 1);
        }
        let cols = (run * BLOCK).min(size.x - at.x);
        Some(Tile { origin, size: UVec2::new(cols, band_rows) })
    }
}

/// Why `part` cannot be launched as a part of a `width` x `height` launch
/// ([`Context::launch_part`](crate::Context::launch_part)): it must be
/// non-empty, inside the launch, and on the 8 x 8 block grid (its origin,
/// and its far edges unless they are the launch's).
pub(crate) fn part_problem(width: u32, height: u32, part: Tile) -> Option<String> {
    let (o, s) = (part.origin, part.size);
    let end = o.as_u64vec2() + s.as_u64vec2();
    if s.x == 0 || s.y == 0 {
        return Some(format!("the part at {o} of size {s} is empty"));
    }
    if end.x > width as u64 || end.y > height as u64 {
        return Some(format!("the part at {o} of size {s} reaches past the launch's edge"));
    }
    let on_grid = |v: u64, edge: u32| v.is_multiple_of(BLOCK as u64) || v == edge as u64;
    if o % BLOCK != UVec2::ZERO || !on_grid(end.x, width) || !on_grid(end.y, height) {
        return Some(format!(
            "the part at {o} of size {s} is not on the 8 x 8 grid of launch indices (its origin, and its far edges unless they are the launch's, must be multiples of 8)"
        ));
    }
    None
}

/// Seconds per launch index, per entry point, as the last tiles measured.
#[derive(Clone, Debug, Default)]
pub(crate) struct Pace {
    per_index: HashMap<u32, f64>,
}

impl Pace {
    /// The indices of the next tile of `entry` under `budget`, after a
    /// tile of `last` indices (`None`: the launch's first tile).
    pub fn next_size(&self, budget: TileBudget, entry: u32, last: Option<u64>) -> u64 {
        match budget {
            TileBudget::Whole => u64::MAX,
            TileBudget::Indices(n) => n.max(1),
            TileBudget::Time(t) => {
                let Some(&s) = self.per_index.get(&entry).filter(|s| **s > 0.0) else {
                    return last.map_or(PROBE_INDICES, |l| l.saturating_mul(MAX_GROWTH));
                };
                let fit = (t.as_secs_f64() / 2.0 / s).clamp(1.0, u64::MAX as f64 / 2.0) as u64;
                // A launch's first tile trusts the last launch's pace (the
                // budget keeps a margin of 8 below a driver's reset).
                match last {
                    Some(l) => fit.min(l.saturating_mul(MAX_GROWTH)),
                    None => fit,
                }
            }
        }
    }

    /// Records that `indices` launch indices of `entry` took `time`.
    pub fn record(&mut self, entry: u32, indices: u64, time: Duration) {
        if indices > 0 {
            self.per_index.insert(entry, time.as_secs_f64() / indices as f64);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index of every launch once, in row-major block order.
    #[test]
    fn tiles_cover_every_index_once() {
        for (w, h) in [(1, 1), (7, 3), (8, 8), (13, 1), (100, 37), (512, 256), (1000, 1)] {
            for n in [1, 64, 100, 640, 5000, 1 << 20] {
                let mut seen = vec![0u8; (w * h) as usize];
                let mut tiler = Tiler::new(Tile::whole(w, h));
                let mut tiles = 0;
                while let Some(t) = tiler.next_tile(n) {
                    assert_eq!(t.origin % BLOCK, UVec2::ZERO, "{w}x{h} n={n}: {t:?}");
                    for i in 0..t.count() {
                        let p = t.index(i);
                        assert!(p.x < w && p.y < h, "{w}x{h} n={n}: {t:?}");
                        seen[(p.y * w + p.x) as usize] += 1;
                    }
                    tiles += 1;
                    assert!(tiles < 100_000);
                }
                assert!(seen.iter().all(|&c| c == 1), "{w}x{h} n={n}");
            }
        }
    }

    #[test]
    fn a_large_budget_is_whole_bands_and_a_small_one_pieces_of_a_band() {
        let mut t = Tiler::new(Tile::whole(100, 37));
        assert_eq!(t.next_tile(u64::MAX), Some(Tile::whole(100, 37)));
        assert_eq!(t.next_tile(u64::MAX), None);
        let mut t = Tiler::new(Tile::whole(100, 37));
        // 13 blocks a band: 2000 indices are two bands.
        assert_eq!(t.next_tile(2000), Some(Tile { origin: UVec2::ZERO, size: UVec2::new(100, 16) }));
        // 200 indices: three blocks of the third band.
        assert_eq!(t.next_tile(200), Some(Tile { origin: UVec2::new(0, 16), size: UVec2::new(24, 8) }));
        // The rest of that band, then bands again.
        assert_eq!(t.next_tile(1 << 20), Some(Tile { origin: UVec2::new(24, 16), size: UVec2::new(76, 8) }));
        assert_eq!(t.next_tile(1 << 20), Some(Tile { origin: UVec2::new(0, 24), size: UVec2::new(100, 13) }));
        assert!(t.finished());
    }

    #[test]
    fn a_1d_launch_is_cut_along_its_row() {
        let mut t = Tiler::new(Tile::whole(1000, 1));
        assert_eq!(t.next_tile(300), Some(Tile { origin: UVec2::ZERO, size: UVec2::new(296, 1) }));
        assert_eq!(t.next_tile(1 << 20), Some(Tile { origin: UVec2::new(296, 0), size: UVec2::new(704, 1) }));
        assert_eq!(t.next_tile(1), None);
    }

    #[test]
    fn a_part_is_cut_from_its_origin() {
        let part = Tile { origin: UVec2::new(16, 8), size: UVec2::new(20, 11) };
        let mut t = Tiler::new(part);
        assert_eq!(t.next_tile(64), Some(Tile { origin: UVec2::new(16, 8), size: UVec2::new(8, 8) }));
        assert_eq!(t.next_tile(1 << 20), Some(Tile { origin: UVec2::new(24, 8), size: UVec2::new(12, 8) }));
        assert_eq!(t.next_tile(1 << 20), Some(Tile { origin: UVec2::new(16, 16), size: UVec2::new(20, 3) }));
        assert!(t.finished());
        assert_eq!(part_problem(36, 19, part), None);
        assert_eq!(part_problem(40, 40, Tile { origin: UVec2::new(16, 8), size: UVec2::new(24, 32) }), None);
        for bad in [
            Tile { origin: UVec2::new(16, 8), size: UVec2::new(20, 11) },
            Tile { origin: UVec2::new(4, 0), size: UVec2::new(8, 8) },
            Tile { origin: UVec2::ZERO, size: UVec2::new(0, 8) },
            Tile { origin: UVec2::new(32, 0), size: UVec2::new(16, 8) },
        ] {
            assert!(part_problem(40, 40, bad).is_some(), "{bad:?}");
        }
    }

    #[test]
    fn the_pace_probes_then_fits_half_the_budget_growing_at_most_fourfold() {
        let mut pace = Pace::default();
        let budget = TileBudget::Time(Duration::from_millis(500));
        assert_eq!(pace.next_size(budget, 0, None), PROBE_INDICES);
        // 0.1 µs an index: 2.5 million fit in half the budget, but the
        // tile after the probe grows only fourfold.
        pace.record(0, PROBE_INDICES, Duration::from_nanos(100 * PROBE_INDICES));
        assert_eq!(pace.next_size(budget, 0, Some(PROBE_INDICES)), 4 * PROBE_INDICES);
        let fit = pace.next_size(budget, 0, Some(1 << 30));
        assert!((2_499_990..=2_500_000).contains(&fit), "{fit}");
        // 1 µs an index: 250,000, under 4x the probe.
        pace.record(0, PROBE_INDICES, Duration::from_micros(PROBE_INDICES));
        assert!((249_990..=250_000).contains(&pace.next_size(budget, 0, Some(PROBE_INDICES))));
        // Another entry point probes afresh.
        assert_eq!(pace.next_size(budget, 1, None), PROBE_INDICES);
        assert_eq!(pace.next_size(TileBudget::Indices(0), 0, None), 1);
        assert_eq!(pace.next_size(TileBudget::Whole, 0, None), u64::MAX);
    }
}
