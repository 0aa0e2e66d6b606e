//! `--setup-only`: each wgpu traversal's setup on one scene, alone. A
//! fresh context per traversal (the compute traversal, then ray queries),
//! its device opened before its first launch, which is timed from its call
//! to its first dispatch (`Timings::setup`: the acceleration builds on the
//! host and the device, the scene's encoding, the link, the uploads). The
//! full run reports the same figures from its own first launches.

use crate::figures::SceneFigures;
use crate::json::Json;
use crate::launches::ms;
use crate::programs::{Workload, scene_with};
use crate::scenes;
use rt_runtime::{Backend, Result, Timings, Traversal};

/// The setups of both traversals on `scene` into `j` and `fig`; says why
/// one was not measured (an adapter without ray queries, an error).
pub(crate) fn measure(
    scene: &scenes::BenchScene,
    cam: scenes::Camera,
    (width, height): (u32, u32),
    j: &mut Json,
    fig: &mut SceneFigures,
) {
    for traversal in [Traversal::Compute, Traversal::RayQuery] {
        let name = traversal.name();
        if traversal == Traversal::RayQuery && !rt_runtime::backend::wgpu::probe_ray_queries() {
            let why = "the adapter has no ray queries (wgpu::Features::EXPERIMENTAL_RAY_QUERY)";
            j.child("skipped").set(name, why);
            continue;
        }
        let first = || -> Result<Timings> {
            let (mut ctx, ..) = scene_with(&scene.mesh, cam, Backend::Wgpu, width, height, Workload::Ao)?;
            ctx.set_traversal(traversal);
            ctx.open_wgpu()?;
            Ok(ctx.launch(0, width, height)?.timings)
        };
        match first() {
            Ok(t) => {
                let o = j.child("first_launch_ms").child(name);
                o.set("setup", ms(t.setup));
                o.set("build", ms(t.build));
                o.set("encode", ms(t.encode));
                o.set("link", ms(t.link));
                o.set("device_accel_build", ms(t.accel));
                let setup = Some(ms(t.setup));
                match traversal {
                    Traversal::RayQuery => fig.rayquery_setup = setup,
                    _ => fig.compute_setup = setup,
                }
                eprintln!(
                    "{name} traversal: setup {:.1} ms (host build {:.1}, encode {:.1}, link {:.1}, device build {:.1})",
                    ms(t.setup),
                    ms(t.build),
                    ms(t.encode),
                    ms(t.link),
                    ms(t.accel)
                );
            }
            Err(e) => {
                eprintln!("{name} traversal: {e}");
                j.child("skipped").set(name, e.to_string());
            }
        }
    }
}
