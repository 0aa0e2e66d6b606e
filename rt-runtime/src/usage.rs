//! The usage report: what each launch did (builds, encodes, links,
//! uploads) and how long it took, handed to a callback the user sets
//! ([`Context::set_usage_report`](crate::Context::set_usage_report); OptiX 6's
//! `rtContextSetUsageReportCallback`), typed and as one line of text.

use crate::backend::wgpu::Traversal;
use crate::backend::{Backend, LaunchReport};
use crate::error::RtError;
use glam::UVec2;
use std::fmt;
use std::time::Duration;

/// What one launch did.
#[derive(Debug)]
pub struct UsageReport<'a> {
    /// The entry point launched.
    pub entry: u32,
    /// The launch's grid: width and height (a 3D launch's height times its
    /// depth).
    pub size: UVec2,
    /// The backend it ran on.
    pub backend: Backend,
    /// The launch's report, or why it failed.
    pub outcome: Result<&'a LaunchReport, &'a RtError>,
    /// Full acceleration builds and refits the launch did.
    pub acceleration_builds: u64,
    /// Refits (a structure updated for moved geometry, not rebuilt).
    pub acceleration_refits: u64,
    /// Whether the launch encoded and uploaded the scene (wgpu; the others
    /// found it on the device), and its geometry too.
    pub scene_encoded: bool,
    /// Whether the launch encoded and uploaded the geometry (wgpu).
    pub geometry_encoded: bool,
    /// Megakernel pipelines the launch created (wgpu; 0 when it reused one).
    pub pipelines_created: u64,
    /// Bytes the launch wrote to the device (wgpu).
    pub upload_bytes: u64,
    /// The wgpu traversal the launch took, and why.
    pub traversal: Option<(Traversal, &'a str)>,
}

/// A duration in milliseconds, for the text.
fn ms(d: Duration) -> String {
    format!("{:.2} ms", d.as_secs_f64() * 1e3)
}

/// A byte count, for the text.
fn bytes(n: u64) -> String {
    match n {
        n if n >= 1 << 20 => format!("{:.1} MiB", n as f64 / (1u64 << 20) as f64),
        n if n >= 1 << 10 => format!("{:.1} KiB", n as f64 / 1024.0),
        n => format!("{n} B"),
    }
}

impl fmt::Display for UsageReport<'_> {
    /// One line: `launch of entry 0, 640x480 on wgpu (compute traversal):
    /// 2 tiles; acceleration: 1 build, 0 refits in 3.10 ms; ...`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "launch of entry {}, {}x{} on {}", self.entry, self.size.x, self.size.y, self.backend.name())?;
        if let Some((t, _)) = self.traversal {
            write!(f, " ({} traversal)", t.name())?;
        }
        let report = match self.outcome {
            Ok(report) => report,
            Err(e) => return write!(f, ": failed: {e}"),
        };
        let t = &report.timings;
        write!(f, ": {} tile{}", report.tiles, if report.tiles == 1 { "" } else { "s" })?;
        write!(
            f,
            "; acceleration: {} build{}, {} refit{} in {}",
            self.acceleration_builds,
            if self.acceleration_builds == 1 { "" } else { "s" },
            self.acceleration_refits,
            if self.acceleration_refits == 1 { "" } else { "s" },
            ms(t.build)
        )?;
        let encoded = match (self.scene_encoded, self.geometry_encoded) {
            (true, true) => "scene and geometry encoded",
            (true, false) => "scene encoded",
            _ => "variables encoded",
        };
        write!(f, "; {encoded} in {}", ms(t.encode))?;
        if self.backend == Backend::Wgpu {
            match self.pipelines_created {
                0 => write!(f, "; pipeline reused")?,
                n => write!(f, "; {n} pipeline{} linked in {}", if n == 1 { "" } else { "s" }, ms(t.link))?,
            }
            write!(f, "; uploaded {}", bytes(self.upload_bytes))?;
        }
        write!(f, "; ran in {}", ms(t.run))?;
        if let Some(k) = t.kernel {
            write!(f, " (kernel {})", ms(k))?;
        }
        write!(f, "; {} rays, {} exceptions", report.rays, report.exceptions.len())
    }
}
