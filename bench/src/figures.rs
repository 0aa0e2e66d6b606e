//! What one scene measured ([`SceneFigures`]), into its JSON object, and
//! the headline ratios reported from every scene's figures.

use crate::json::Json;

/// What one scene measured, for the top-level ratios.
#[derive(Default)]
pub(crate) struct SceneFigures {
    pub(crate) cpu: Option<f64>,
    /// The CPU backend with ray generation programs run lane-wise, and
    /// one launch index at a time (one of them is `cpu`).
    pub(crate) cpu_lanes: Option<f64>,
    pub(crate) cpu_scalar: Option<f64>,
    pub(crate) obvhs: Option<f64>,
    /// Embree's best mode: the faster of `embree1` and `embree16`.
    pub(crate) embree: Option<f64>,
    /// `rtcIntersect1` (single rays) and `rtcIntersect16` (4x4 tiles).
    pub(crate) embree1: Option<f64>,
    pub(crate) embree16: Option<f64>,
    /// The CPU backend's tree and walk without its programs, and its rays.
    pub(crate) walk: Option<f64>,
    pub(crate) walk_rays: u64,
    /// The same tree walked by 16-ray packets (4x4 tiles, then their AO
    /// rays), as Embree's `rtcIntersect16` is driven.
    pub(crate) packet_walk: Option<f64>,
    /// The primary rays alone (no AO rays traced), one by one and in
    /// packets: where packets should pay most.
    pub(crate) walk_primary: Option<f64>,
    pub(crate) packet_walk_primary: Option<f64>,
    pub(crate) wgpu: Option<f64>,
    pub(crate) handwritten: Option<f64>,
    /// Rays per CPU second of the process (lavapipe's threads), which
    /// load from other processes does not change.
    pub(crate) wgpu_per_cpu_s: Option<f64>,
    pub(crate) handwritten_per_cpu_s: Option<f64>,
    /// Rays per second of the device's own time (timestamp queries): the
    /// kernels alone, without submission, waiting and read-back.
    pub(crate) wgpu_kernel: Option<f64>,
    pub(crate) handwritten_kernel: Option<f64>,
    /// The hand-written kernel over the BVH2 instead of the CWBVH.
    pub(crate) handwritten_bvh2: Option<f64>,
    pub(crate) handwritten_bvh2_kernel: Option<f64>,
    /// The megakernel with the ray-query traversal, and the hand-written
    /// ray-query kernel (wall clock, device time).
    pub(crate) rayquery: Option<f64>,
    pub(crate) rayquery_kernel: Option<f64>,
    pub(crate) rayquery_handwritten: Option<f64>,
    pub(crate) rayquery_handwritten_kernel: Option<f64>,
    /// Each traversal's setup in milliseconds: its first launch's time to
    /// its first dispatch (`Timings::setup`: acceleration builds on the
    /// host and the device, encoding, link, uploads).
    pub(crate) compute_setup: Option<f64>,
    pub(crate) rayquery_setup: Option<f64>,
    /// Throughput of launches cut into tiles (the default) over whole
    /// ones, per backend.
    pub(crate) cpu_tiled_vs_whole: Option<f64>,
    pub(crate) wgpu_tiled_vs_whole: Option<f64>,
    /// Throughput with every exception kind off over every kind on.
    pub(crate) cpu_exceptions_off_vs_on: Option<f64>,
    pub(crate) wgpu_exceptions_off_vs_on: Option<f64>,
}

/// A scene's figures into its JSON object.
pub(crate) fn record_figures(j: &mut Json, fig: &SceneFigures) {
    for (k, v) in [
        ("cpu", fig.cpu),
        ("cpu_lanes", fig.cpu_lanes),
        ("cpu_scalar", fig.cpu_scalar),
        ("wgpu", fig.wgpu),
        ("obvhs", fig.obvhs),
        ("embree", fig.embree),
        ("embree_intersect1", fig.embree1),
        ("embree_intersect16", fig.embree16),
        ("cpu_walk_only", fig.walk),
        ("cpu_packet_walk_only", fig.packet_walk),
        ("cpu_walk_only_primary", fig.walk_primary),
        ("cpu_packet_walk_only_primary", fig.packet_walk_primary),
        ("handwritten_wgsl", fig.handwritten),
        ("handwritten_bvh2_wgsl", fig.handwritten_bvh2),
        ("rayquery", fig.rayquery),
        ("handwritten_rayquery", fig.rayquery_handwritten),
    ] {
        j.child("mrays_per_s").set(k, v);
    }
    // The kernels alone (device timestamps), and the megakernel's Grays/s
    // by them: the figure a GPU is judged by.
    for (k, v) in [
        ("wgpu", fig.wgpu_kernel),
        ("handwritten_wgsl", fig.handwritten_kernel),
        ("handwritten_bvh2_wgsl", fig.handwritten_bvh2_kernel),
        ("rayquery", fig.rayquery_kernel),
        ("handwritten_rayquery", fig.rayquery_handwritten_kernel),
    ] {
        j.child("kernel_mrays_per_s").set(k, v);
    }
    // Below 1: the ray-query traversal starts its first dispatch sooner.
    let setup = j.child("setup_ms");
    setup.set("compute", fig.compute_setup);
    setup.set("rayquery", fig.rayquery_setup);
    j.set("rayquery_setup_over_compute_setup", ratio(fig.rayquery_setup, fig.compute_setup));
    j.set("wgpu_grays_per_s", fig.wgpu_kernel.or(fig.wgpu).map(|m| m / 1e3));
    if fig.wgpu.is_some() {
        j.set("wgpu_grays_timed_by", if fig.wgpu_kernel.is_some() { "device timestamps" } else { "wall clock" });
    }
}

/// One of the headline ratios, from one scene's figures.
type RatioOf = fn(&SceneFigures) -> Option<f64>;

/// `a / b` where both were measured.
fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    Some(a? / b?)
}

/// Geometric mean of the ratios that exist, with how many there were.
fn geomean(rs: &[Option<f64>]) -> Option<f64> {
    let v: Vec<f64> = rs.iter().flatten().copied().collect();
    (!v.is_empty()).then(|| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp())
}

/// The headline ratios on the bunny, and their geometric means over the
/// scenes where both sides were measured; how each side's speed holds from
/// the bunny to the wall; and the CPU backend's instruction set.
pub(crate) fn record_ratios(json: &mut Json, figures: &[(&str, SceneFigures)]) {
    let pick = |name: &str| figures.iter().find(|(n, _)| *n == name).map(|(_, f)| f);
    let ratios: [(&str, RatioOf); 21] = [
        ("cpu_vs_obvhs", |f| ratio(f.cpu, f.obvhs)),
        // Against Embree's best mode (the faster of rtcIntersect1 and
        // rtcIntersect16), and against its single rays alone.
        ("cpu_vs_embree", |f| ratio(f.cpu, f.embree)),
        ("cpu_vs_embree_intersect1", |f| ratio(f.cpu, f.embree1)),
        // Ray generation lane-wise against one launch index at a time
        // (above 1: lane-wise is faster).
        ("cpu_lanes_vs_scalar", |f| ratio(f.cpu_lanes, f.cpu_scalar)),
        // The CPU backend's walk without programs against Embree's best.
        ("cpu_walk_only_vs_embree", |f| ratio(f.walk, f.embree)),
        // What 16-ray packets give the same walk (above 1: packets pay),
        // and the packet walk against Embree's own packets.
        ("cpu_packet_walk_vs_walk", |f| ratio(f.packet_walk, f.walk)),
        ("cpu_packet_walk_vs_walk_primary", |f| ratio(f.packet_walk_primary, f.walk_primary)),
        ("cpu_packet_walk_vs_embree16", |f| ratio(f.packet_walk, f.embree16)),
        ("megakernel_vs_handwritten", |f| ratio(f.wgpu, f.handwritten)),
        // The same, as rays per CPU second of this process: steady under
        // load from other processes, which the wall-clock ratio is not.
        ("megakernel_vs_handwritten_cpu_time", |f| ratio(f.wgpu_per_cpu_s, f.handwritten_per_cpu_s)),
        // The kernels alone, by the device's timestamps (on a GPU, where
        // submission and read-back are a large part of a short launch).
        ("megakernel_vs_handwritten_kernel", |f| ratio(f.wgpu_kernel, f.handwritten_kernel)),
        // What 8-wide nodes give a kernel on this adapter (device time;
        // above 1: the CWBVH kernel is faster).
        ("handwritten_cwbvh_vs_bvh2_kernel", |f| ratio(f.handwritten_kernel, f.handwritten_bvh2_kernel)),
        // The megakernel's two traversals on one adapter (above 1: ray
        // queries are faster), and the ray-query megakernel against the
        // hand-written ray-query kernel (goal >= 0.9).
        ("rayquery_vs_compute", |f| ratio(f.rayquery, f.wgpu)),
        ("rayquery_vs_compute_kernel", |f| ratio(f.rayquery_kernel, f.wgpu_kernel)),
        ("megakernel_rayquery_vs_handwritten", |f| ratio(f.rayquery, f.rayquery_handwritten)),
        ("megakernel_rayquery_vs_handwritten_kernel", |f| ratio(f.rayquery_kernel, f.rayquery_handwritten_kernel)),
        // The ray-query traversal's setup (first launch to first dispatch)
        // over the compute traversal's: below 1, ray queries start sooner.
        ("rayquery_setup_over_compute_setup", |f| ratio(f.rayquery_setup, f.compute_setup)),
        // Launches cut into tiles (the default budget) against whole ones
        // (above 1: tiles are faster).
        ("cpu_tiled_vs_whole_launch", |f| f.cpu_tiled_vs_whole),
        ("wgpu_tiled_vs_whole_launch", |f| f.wgpu_tiled_vs_whole),
        ("cpu_exceptions_off_vs_on", |f| f.cpu_exceptions_off_vs_on),
        ("wgpu_exceptions_off_vs_on", |f| f.wgpu_exceptions_off_vs_on),
    ];
    for (key, r) in ratios {
        json.set(key, pick("bunny").and_then(r));
        let all: Vec<Option<f64>> = figures.iter().map(|(_, f)| r(f)).collect();
        json.set(&format!("{key}_geomean"), geomean(&all));
    }
    // How each side's speed holds from the bunny (69k triangles) to the
    // wall (2M): Mrays/s on the wall over Mrays/s on the bunny.
    let scaling = |side: fn(&SceneFigures) -> Option<f64>| {
        ratio(pick("bunny_wall_2m").and_then(side), pick("bunny").and_then(side))
    };
    json.set("cpu_scaling", scaling(|f| f.cpu));
    json.set("embree_scaling", scaling(|f| f.embree));
    json.set("cpu_simd", rt_runtime::accel::CpuSimd::current().name());
    json.set(
        "obvhs_vs_embree_geomean",
        geomean(&figures.iter().map(|(_, f)| ratio(f.obvhs, f.embree)).collect::<Vec<_>>()),
    );
}
