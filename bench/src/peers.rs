//! The primary + ambient-occlusion workload as the CPU peers trace it:
//! per pixel one primary ray and, at a hit, one cosine-weighted AO ray
//! (closest hit, unbounded), rayon over rows like the CPU backend. The AO
//! directions come from the same hash as the bench's `ambient_occlusion`
//! program, so every side traces the same rays.

use crate::scenes::Camera;
use glam::{Vec2, Vec3};
use obvhs::triangle::Triangle;
use rayon::prelude::*;
use rt_std::prelude::faceforward;
use std::time::{Duration, Instant};

/// What one run traced.
pub struct AoRun {
    /// Rays traced: primary rays plus AO rays.
    pub rays: u64,
    pub time: Duration,
    /// Per pixel, the primary hit distance (infinity on a miss).
    pub primary_t: Vec<f32>,
    /// Per pixel, whether the AO ray hit something.
    pub ao_hit: Vec<bool>,
}

/// The primary rays' `tmin`, as the bench's `pinhole` program sets it.
const PRIMARY_TMIN: f32 = 1e-4;

/// The primary ray's direction through pixel `(x, y)`, as `pinhole`
/// computes it.
fn primary_direction((_, u, v, w): Camera, x: u32, y: u32, width: u32, height: u32) -> Vec3 {
    let d = (Vec2::new(x as f32, y as f32) + 0.5) / Vec2::new(width as f32, height as f32) * 2.0 - 1.0;
    (d.x * u + d.y * v + w).normalize()
}

/// The AO ray (origin, direction) of a primary hit at `t` along `dir`
/// with triangle `prim`, for the pixel of linear index `pixel`, as the
/// bench's `ambient_occlusion` program computes it.
fn ao_ray(tris: &[Triangle], eye: Vec3, dir: Vec3, t: f32, prim: u32, pixel: u32) -> (Vec3, Vec3) {
    let p = eye + t * dir;
    let n = Vec3::from(tris[prim as usize].compute_normal()).normalize();
    let n = faceforward(n, dir, n);
    let h1 = crate::programs::hash(pixel);
    let h2 = crate::programs::hash(h1);
    let ao = crate::programs::cosine_direction(n, (h1 >> 8) as f32 / 16777216.0, (h2 >> 8) as f32 / 16777216.0);
    (p + n * 1e-4, ao)
}

/// Traces the workload with `closest(origin, direction, tmin)`, which
/// returns the closest hit's distance and triangle index (into `tris`).
pub fn trace_ao<F>(tris: &[Triangle], cam: Camera, width: u32, height: u32, closest: F) -> AoRun
where
    F: Fn(Vec3, Vec3, f32) -> Option<(f32, u32)> + Sync,
{
    let eye = cam.0;
    let pixels = (width * height) as usize;
    let mut primary_t = vec![f32::INFINITY; pixels];
    let mut ao_hit = vec![false; pixels];
    let start = Instant::now();
    let rays: u64 = primary_t
        .par_chunks_mut(width as usize)
        .zip(ao_hit.par_chunks_mut(width as usize))
        .enumerate()
        .map(|(y, (ts, aos))| {
            let y = y as u32;
            let mut rays = 0u64;
            for x in 0..width {
                let dir = primary_direction(cam, x, y, width, height);
                rays += 1;
                if let Some((t, prim)) = closest(eye, dir, PRIMARY_TMIN) {
                    ts[x as usize] = t;
                    let (o, d) = ao_ray(tris, eye, dir, t, prim, x + y * width);
                    rays += 1;
                    aos[x as usize] = closest(o, d, 0.0).is_some();
                }
            }
            rays
        })
        .sum();
    AoRun { rays, time: start.elapsed(), primary_t, ao_hit }
}

/// The workload in packets: each 4x4 tile's primary rays through
/// `closest16` together, then the AO rays of the tile's hits together
/// (Embree's `rtcIntersect16`; the same rays as [`trace_ao`]).
pub fn trace_ao16<F>(tris: &[Triangle], cam: Camera, width: u32, height: u32, closest16: F) -> AoRun
where
    F: Fn(&[(Vec3, Vec3, f32)], bool, &mut [Option<(f32, u32)>]) + Sync,
{
    let eye = cam.0;
    let pixels = (width * height) as usize;
    let mut primary_t = vec![f32::INFINITY; pixels];
    let mut ao_hit = vec![false; pixels];
    let start = Instant::now();
    let tiles_x = width.div_ceil(4);
    let tiles = (tiles_x * height.div_ceil(4)) as usize;
    // Per tile: rays traced, and (pixel, primary distance, AO hit).
    type Tile = (u64, Vec<(usize, f32, bool)>);
    let results: Vec<Tile> = (0..tiles)
        .into_par_iter()
        .with_min_len(16)
        .map(|tile| {
            let (tx, ty) = (tile as u32 % tiles_x * 4, tile as u32 / tiles_x * 4);
            let mut pixels = Vec::with_capacity(16);
            let mut rays = Vec::with_capacity(16);
            for y in ty..(ty + 4).min(height) {
                for x in tx..(tx + 4).min(width) {
                    pixels.push((x, y));
                    rays.push((eye, primary_direction(cam, x, y, width, height), PRIMARY_TMIN));
                }
            }
            let mut hits = [None; 16];
            closest16(&rays, true, &mut hits);
            let mut traced = rays.len() as u64;
            let (mut ao_rays, mut ao_of) = (Vec::with_capacity(16), Vec::with_capacity(16));
            let mut out = Vec::with_capacity(16);
            for (k, &(x, y)) in pixels.iter().enumerate() {
                let i = (y * width + x) as usize;
                let Some((t, prim)) = hits[k] else {
                    out.push((i, f32::INFINITY, false));
                    continue;
                };
                let (o, d) = ao_ray(tris, eye, rays[k].1, t, prim, x + y * width);
                ao_rays.push((o, d, 0.0));
                ao_of.push(out.len());
                out.push((i, t, false));
            }
            if !ao_rays.is_empty() {
                let mut ao_hits = [None; 16];
                closest16(&ao_rays, false, &mut ao_hits);
                traced += ao_rays.len() as u64;
                for (k, &o) in ao_of.iter().enumerate() {
                    out[o].2 = ao_hits[k].is_some();
                }
            }
            (traced, out)
        })
        .collect();
    let mut rays = 0;
    for (traced, out) in results {
        rays += traced;
        for (i, t, ao) in out {
            primary_t[i] = t;
            ao_hit[i] = ao;
        }
    }
    AoRun { rays, time: start.elapsed(), primary_t, ao_hit }
}

/// obvhs's own CWBVH over `tris` (`medium_build`), and its build time.
pub fn obvhs_cwbvh(tris: &[Triangle]) -> (obvhs::cwbvh::CwBvh, Duration) {
    let mut core = Duration::ZERO;
    let t = Instant::now();
    let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(tris, obvhs::BvhBuildParams::medium_build(), &mut core);
    (bvh, t.elapsed())
}

/// The workload through obvhs's CWBVH traversal and its `Triangle::intersect`.
pub fn obvhs_ao(bvh: &obvhs::cwbvh::CwBvh, tris: &[Triangle], cam: Camera, width: u32, height: u32) -> AoRun {
    use obvhs::ray::{Ray, RayHit};
    trace_ao(tris, cam, width, height, |o, d, tmin| {
        let mut hit = RayHit::none();
        let ray = Ray::new(o.into(), d.into(), tmin, f32::INFINITY);
        bvh.ray_traverse(ray, &mut hit, |r, id| tris[bvh.primitive_indices[id] as usize].intersect(r))
            .then(|| (hit.t, bvh.primitive_indices[hit.primitive_id as usize]))
    })
}

/// Pixels where two runs disagree: (primary hit or distance, AO hit).
/// Distances agree within 1e-4 of the distance (plus 1e-6 absolute).
pub fn mismatches(a: &AoRun, b: &AoRun) -> (usize, usize) {
    let primary = a
        .primary_t
        .iter()
        .zip(&b.primary_t)
        .filter(|(x, y)| match (x.is_finite(), y.is_finite()) {
            (true, true) => (*x - *y).abs() > 1e-4 * x.abs() + 1e-6,
            (hx, hy) => hx != hy,
        })
        .count();
    let ao = a.ao_hit.iter().zip(&b.ao_hit).filter(|(x, y)| x != y).count();
    (primary, ao)
}

/// The median of some durations.
pub fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

/// CPU time this process has used (all threads, user + system), from
/// `/proc/self/stat` (zero where there is none). Under load from other
/// processes it measures work rather than waiting, so kernel comparisons
/// on lavapipe (whose threads do the work in this process) stay stable.
pub fn process_cpu_time() -> Duration {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else { return Duration::ZERO };
    // Fields after the command name (which may hold spaces): utime and
    // stime are the 14th and 15th fields, in clock ticks (100 a second).
    let Some(rest) = stat.rsplit_once(')').map(|(_, r)| r) else { return Duration::ZERO };
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<u64>().ok()).unwrap_or(0);
    Duration::from_millis((ticks(11) + ticks(12)) * 10)
}
