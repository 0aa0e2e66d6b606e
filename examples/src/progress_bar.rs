//! The progress bar of `tour` and `render`: samples per pixel done, moving
//! within a launch as its tiles finish ([`crate::scene::Progress`]).

use crate::scene::Progress;
use indicatif::{ProgressBar, ProgressStyle};

/// Steps of the bar a launch is worth.
const STEPS: u64 = 1000;

/// A bar for a render of `frames` launches, named `prefix`.
pub fn spp_bar(prefix: &str, frames: u32) -> ProgressBar {
    let bar = ProgressBar::new(frames as u64 * STEPS);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>12} [{bar:30}] {msg} spp, {elapsed} (eta {eta})")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_prefix(prefix.to_string());
    bar.set_message(format!("0/{frames}"));
    bar
}

/// Moves `bar` to `p`.
pub fn show(bar: &ProgressBar, p: Progress) {
    bar.set_position((p.fraction() * (p.frames as u64 * STEPS) as f64) as u64);
    bar.set_message(format!("{}/{}", p.frames_done(), p.frames));
}
