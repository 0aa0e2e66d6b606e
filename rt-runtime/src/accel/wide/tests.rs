//! The SIMD layout's walk against the reference tests, on every
//! instruction set this CPU has.

use super::isa::Isa;
use super::testing::Triangles;
use glam::Vec3;

/// A small deterministic generator (xorshift), uniform in `[-r, r]`.
struct Rng(u64);
impl Rng {
    fn f(&mut self, r: f32) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0) * r
    }
    fn v(&mut self, r: f32) -> Vec3 {
        Vec3::new(self.f(r), self.f(r), self.f(r))
    }
}

fn paths() -> Vec<Isa> {
    Isa::ALL.into_iter().filter(|i| i.supported()).collect()
}

/// Small random triangles, with degenerate ones (a point, a line) and
/// NaN ones among them.
fn soup(n: usize, rng: &mut Rng) -> Vec<[Vec3; 3]> {
    (0..n)
        .map(|i| {
            let c = rng.v(4.0);
            let (a, b) = (c + rng.v(0.4), c + rng.v(0.4));
            match i % 50 {
                0 => [c, c, c],
                1 => [c, a, c + (a - c) * 2.0],
                2 => [c, a, Vec3::new(f32::NAN, 0.0, 0.0)],
                _ => [c, a, b],
            }
        })
        .collect()
}

/// Every path finds the brute-force closest hit: the same distance and
/// barycentrics bit for bit, the same triangle unless two tie at that
/// distance; degenerate and NaN triangles are never hit.
#[test]
fn every_path_finds_the_brute_force_closest_hit() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let tris = soup(3000, &mut rng);
    let mesh = Triangles::new(tris.clone());
    let (nodes, leaves, depth) = mesh.shape();
    assert!(nodes > 100 && leaves > 750 && depth > 2, "{nodes} nodes, {leaves} leaves, depth {depth}");
    let mut hits = 0;
    for i in 0..4000 {
        let o = rng.v(6.0);
        let mut d = rng.v(4.0) - o;
        if i % 8 == 0 {
            d[i % 3] = 0.0;
        }
        if i % 16 == 1 {
            d[(i + 1) % 3] = -0.0;
        }
        let tmin = if i % 5 == 0 { 0.5 } else { 0.0 };
        let want = mesh.closest_brute_force(o, d, tmin, f32::INFINITY);
        for isa in paths() {
            let got = mesh.closest(isa, o, d, tmin, f32::INFINITY);
            match (got, want) {
                (Some(g), Some(w)) => {
                    assert_eq!(g.0.to_bits(), w.0.to_bits(), "{isa:?}: ray {o} + t {d}: {g:?} against {w:?}");
                    assert!(
                        g.1 == w.1 || mesh.hits_at(g.1, o, d, tmin, w.0),
                        "{isa:?}: ray {o} + t {d}: {g:?} against {w:?}"
                    );
                    if g.1 == w.1 {
                        assert_eq!((g.2.to_bits(), g.3.to_bits()), (w.2.to_bits(), w.3.to_bits()));
                    }
                    assert!(g.1 % 50 > 2, "{isa:?}: hit degenerate triangle {}", g.1);
                }
                (None, None) => {}
                _ => panic!("{isa:?}: ray {o} + t {d}: {got:?} against {want:?}"),
            }
        }
        hits += want.is_some() as u32;
    }
    assert!(hits > 1000, "only {hits} of 4000 rays hit");
}

/// A limited `tmax` is respected: no hit at or beyond it.
#[test]
fn every_path_stops_at_tmax() {
    let mut rng = Rng(0x2545f4914f6cdd1d);
    let mesh = Triangles::new(soup(1000, &mut rng));
    for _ in 0..2000 {
        let o = rng.v(6.0);
        let d = rng.v(4.0) - o;
        let tmax = rng.f(1.0).abs();
        let want = mesh.closest_brute_force(o, d, 0.0, tmax);
        for isa in paths() {
            let got = mesh.closest(isa, o, d, 0.0, tmax);
            assert_eq!(got.map(|g| g.0.to_bits()), want.map(|w| w.0.to_bits()), "{isa:?}");
        }
    }
}

/// A grid of triangles in a plane: rays through its vertices and edges
/// (where two to six triangles meet) always hit, on every path.
#[test]
fn no_ray_slips_through_shared_edges_or_vertices() {
    let n = 24;
    let p = |i: usize, j: usize| Vec3::new(i as f32 * 0.37 - 4.0, j as f32 * 0.29 - 3.0, 0.1 * (i as f32 * 0.7).sin());
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            tris.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    let mesh = Triangles::new(tris);
    let mut rng = Rng(0x853c49e6748fea9b);
    for k in 0..6000 {
        let (i, j) = (1 + k % (n - 1), 1 + (k / 7) % (n - 1));
        // A vertex, or a point on an edge (horizontal, vertical, diagonal).
        let s = rng.f(1.0).abs();
        let target = match k % 4 {
            0 => p(i, j),
            1 => p(i, j) + (p(i + 1, j) - p(i, j)) * s,
            2 => p(i, j) + (p(i, j + 1) - p(i, j)) * s,
            _ => p(i, j) + (p(i + 1, j + 1) - p(i, j)) * s,
        };
        let o = target + Vec3::new(rng.f(3.0), rng.f(3.0), 2.0 + rng.f(1.0).abs());
        let d = target - o;
        for isa in paths() {
            assert!(
                mesh.closest(isa, o, d, 0.0, f32::INFINITY).is_some(),
                "{isa:?}: ray {o} + t {d} slips through {target}"
            );
        }
    }
}

/// The same mesh walked by the old traversal (obvhs's CWBVH) gives the
/// same hits: the layout changes nothing users see.
#[test]
fn the_walk_agrees_with_the_cwbvh_walk() {
    let mut rng = Rng(0xda942042e4dd58b5);
    let mesh = Triangles::new(soup(2000, &mut rng));
    for _ in 0..3000 {
        let o = rng.v(6.0);
        let d = rng.v(4.0) - o;
        let want = mesh.closest_cwbvh(o, d, 0.0, f32::INFINITY);
        for isa in paths() {
            let got = mesh.closest(isa, o, d, 0.0, f32::INFINITY);
            assert_eq!(got.map(|g| g.0.to_bits()), want.map(|w| w.0.to_bits()), "{isa:?}");
        }
    }
}
