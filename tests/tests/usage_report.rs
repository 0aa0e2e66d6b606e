//! The usage report (`Context::set_usage_report`, OptiX's
//! `rtContextSetUsageReportCallback`): after every launch, what it built,
//! encoded, linked and uploaded, as counts that change with what the host
//! changed, and as one line of text; a failed launch is reported too.

use glam::{Vec3, Vec4};
use rt_runtime::*;
use rt_std::prelude::*;
use rt_tests::meshes::bumpy_grid;
use rt_tests::targets::On;
use std::sync::{Arc, Mutex};

#[rt_payload]
pub struct Shade {
    pub c: Vec3,
}

#[rt_program(ray_generation)]
pub fn camera(#[var] top: Object, #[var] mut out: RwBuffer2d<Vec4>) {
    let idx = launch_index();
    let p = (idx.as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Shade { c: Vec3::ZERO };
    rt_trace(top, Ray::new(vec3(p.x, p.y, 3.0), vec3(0.0, 0.0, -1.0), 0, 0.0, f32::INFINITY), &mut prd);
    out[idx] = prd.c.extend(1.0);
}

#[rt_program(closest_hit)]
pub fn white(prd: &mut Shade) {
    prd.c = Vec3::ONE;
}

#[rt_program(miss)]
pub fn black(prd: &mut Shade) {
    prd.c = Vec3::ZERO;
}

/// What the reports said: (builds, refits, scene encoded, pipelines, failed, text).
type Seen = Arc<Mutex<Vec<(u64, u64, bool, u64, bool, String)>>>;

#[test]
fn every_launch_is_reported_with_what_it_did() {
    for on in [On::CPU, On::COMPUTE] {
        let seen: Seen = Arc::default();
        let mut ctx = on.context();
        let log = seen.clone();
        ctx.set_usage_report(Some(Box::new(move |r: &UsageReport| {
            let text = r.to_string();
            log.lock().unwrap().push((
                r.acceleration_builds,
                r.acceleration_refits,
                r.scene_encoded,
                r.pipelines_created,
                r.outcome.is_err(),
                text,
            ))
        })));
        let g = ctx.create_triangles(bumpy_grid(8)).unwrap();
        let m = ctx.create_material();
        let ch = ctx.create_program(&white::PROGRAM);
        ctx.set_closest_hit_program(m, 0, ch).unwrap();
        let gi = ctx.create_geometry_instance(g, &[m]).unwrap();
        let top = ctx.create_geometry_group(&[gi], Acceleration::default()).unwrap();
        ctx.set_var(Scope::Context, "top", top).unwrap();
        let out = ctx.create_buffer_2d::<Vec4>(BufferType::Output, 16, 16).unwrap();
        ctx.set_var(Scope::Context, "out", out).unwrap();
        let rg = ctx.create_program(&camera::PROGRAM);
        ctx.set_ray_generation_program(0, rg).unwrap();
        let miss = ctx.create_program(&black::PROGRAM);
        ctx.set_miss_program(0, miss).unwrap();
        ctx.launch(0, 16, 16).unwrap();
        ctx.launch(0, 16, 16).unwrap();
        let moved: Vec<Vec3> = bumpy_grid(8).positions.iter().map(|p| *p + Vec3::Z * 0.01).collect();
        ctx.set_triangle_positions(g, moved).unwrap();
        ctx.launch(0, 16, 16).unwrap();
        assert!(ctx.launch(0, 0, 16).is_err());
        let seen = seen.lock().unwrap();
        let gpu = on != Backend::Cpu;
        let name = on.name();
        assert_eq!(seen.len(), 4, "{name}");
        // The first launch builds and links; the second reuses all; moved
        // vertices refit (and encode the geometry again on wgpu).
        assert_eq!((seen[0].0, seen[0].1, seen[0].2, seen[0].3, seen[0].4), (1, 0, gpu, gpu as u64, false), "{name}");
        assert_eq!((seen[1].0, seen[1].1, seen[1].2, seen[1].3, seen[1].4), (0, 0, false, 0, false), "{name}");
        assert_eq!((seen[2].0, seen[2].1, seen[2].3, seen[2].4), (0, 1, 0, false), "{name}");
        assert!(seen[3].4, "{name}");
        let first = &seen[0].5;
        assert!(first.starts_with(&format!("launch of entry 0, 16x16 on {}", on.backend.name())), "{first}");
        assert!(first.contains("1 tile; acceleration: 1 build, 0 refits in "), "{first}");
        assert!(first.contains("; 256 rays, 0 exceptions"), "{first}");
        if gpu {
            assert!(first.contains("(compute traversal)") && first.contains("1 pipeline linked in "), "{first}");
            assert!(seen[1].5.contains("pipeline reused"), "{}", seen[1].5);
        }
        assert!(seen[3].5.contains(": failed: launch of 0x16: "), "{}", seen[3].5);
    }
}
