//! The command line: [`Args`], and what its options mean for a run.

use crate::tour;
use clap::Parser;

#[derive(Parser)]
pub(crate) struct Args {
    /// A small image, fewer repetitions, and only what lavapipe does in
    /// seconds (under 3 minutes on the 2-core CI VM).
    #[arg(long)]
    pub(crate) quick: bool,
    /// Print one JSON object on stdout (the table goes to stderr).
    #[arg(long)]
    pub(crate) json: bool,
    /// Image width (default 1920, or 320 with --quick).
    #[arg(long)]
    pub(crate) width: Option<u32>,
    /// Image height (default 1080, or 240 with --quick).
    #[arg(long)]
    pub(crate) height: Option<u32>,
    /// Backends to measure.
    #[arg(long, value_delimiter = ',', default_value = "cpu,wgpu")]
    pub(crate) backends: Vec<String>,
    /// Scenes to measure (bunny, teapot, cornell_box, bunny_wall_2m), or
    /// `none` (the bunny's primary-ray figures run with the bunny).
    #[arg(long, value_delimiter = ',')]
    pub(crate) scenes: Vec<String>,
    /// Scenes with more triangles than this skip the wgpu backend and the
    /// hand-written kernel (default: no limit; the scene's sections each
    /// fit lavapipe's 128 MiB binding, so the 2M-triangle wall runs too).
    #[arg(long)]
    pub(crate) wgpu_max_triangles: Option<usize>,
    /// Leave the Embree peer out.
    #[arg(long)]
    pub(crate) no_embree: bool,
    /// Never install Embree (by default a root run without libembree3
    /// installs Debian's package, as bench/setup.sh does).
    #[arg(long)]
    pub(crate) no_install: bool,
    /// Tour examples whose megakernel link to time: `auto` (the default:
    /// the four that link in seconds with --quick, plus cornell and bunny
    /// without), `fast`, `all`, `none`, or names.
    #[arg(long, value_delimiter = ',', default_value = "auto")]
    pub(crate) tour_links: Vec<String>,
    /// Only the per-scene traversal figures: no primary-ray or build
    /// figures, no lowering times (for profiling the traversal alone).
    #[arg(long)]
    pub(crate) traversal_only: bool,
    /// Only the wgpu traversals' setup, per scene: a first launch with the
    /// compute traversal, then one with ray queries, each on a fresh
    /// context, timed from its call to its first dispatch (ratio
    /// `rayquery_setup_over_compute_setup`). Nothing else is measured.
    #[arg(long)]
    pub(crate) setup_only: bool,
    /// Measure nothing: run N launches of the first scene's AO workload on
    /// the CPU backend (in the mode `RT_CPU_EXEC` names) after the one
    /// that builds its tree, for a profiler to count (`profile.rs`).
    #[arg(long, value_name = "N")]
    pub(crate) profile_cpu: Option<usize>,
    /// Use Mesa's usual on-disk shader cache (by default the bench gives
    /// Mesa a fresh one, so each kernel's first compile is cold).
    #[arg(long)]
    pub(crate) warm_shader_cache: bool,
    /// Write SVG charts of the Mrays/s figures into this directory
    /// (mrays_by_scene.svg, mrays_vs_triangles.svg).
    #[arg(long, value_name = "DIR")]
    pub(crate) plot: Option<std::path::PathBuf>,
    /// Measure nothing: chart the JSON an earlier --json run printed
    /// (needs --plot).
    #[arg(long, value_name = "FILE.json", requires = "plot")]
    pub(crate) from: Option<std::path::PathBuf>,
}

impl Args {
    /// The image size: `--width` and `--height`, else 1920x1080 (320x240
    /// with `--quick`).
    pub(crate) fn resolution(&self) -> (u32, u32) {
        match (self.width, self.height) {
            (Some(w), Some(h)) => (w, h),
            _ if self.quick => (320, 240),
            _ => (1920, 1080),
        }
    }

    /// Repetitions of each measurement.
    pub(crate) fn reps(&self) -> usize {
        if self.quick { 3 } else { 5 }
    }

    /// Whether backend `name` (`cpu` or `wgpu`) is measured.
    pub(crate) fn measures(&self, name: &str) -> bool {
        self.backends.iter().any(|b| b == name)
    }

    /// Whether scene `name` is measured: every scene without `--scenes`,
    /// none with `--scenes none`.
    pub(crate) fn measures_scene(&self, name: &str) -> bool {
        let no_scenes = self.scenes.iter().any(|s| s == "none");
        !no_scenes && (self.scenes.is_empty() || self.scenes.iter().any(|s| s == name))
    }

    /// The tour examples whose megakernel link to time (`--tour-links`).
    pub(crate) fn tour_link_names(&self) -> Vec<String> {
        match self.tour_links.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
            ["none"] => Vec::new(),
            ["auto"] if self.quick => tour::FAST.iter().map(|s| s.to_string()).collect(),
            ["auto"] => tour::FAST.iter().chain(&tour::MEDIUM).map(|s| s.to_string()).collect(),
            ["fast"] => tour::FAST.iter().map(|s| s.to_string()).collect(),
            ["all"] => examples::EXAMPLES.iter().map(|e| e.name.to_string()).collect(),
            _ => self.tour_links.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_without_plot_is_an_argument_error() {
        let e = Args::try_parse_from(["rt-bench", "--from", "run.json"]).err().expect("--from needs --plot");
        assert_eq!(e.kind(), clap::error::ErrorKind::MissingRequiredArgument);
        assert!(Args::try_parse_from(["rt-bench", "--from", "run.json", "--plot", "plots"]).is_ok());
    }
}
