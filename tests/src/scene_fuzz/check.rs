//! The comparison of two backends' results for one graph, and the rays it
//! skips: those where the backends may legitimately differ.
//!
//! Skipped (ambiguous) rays, found by walking every path of the graph
//! (all of a selector's children, masks ignored: a superset of what a ray
//! may meet) with the ray in each instance's object space:
//! - within [`EDGE_EPS`] (barycentric) of a triangle's edge, or nearly in
//!   its plane (|cos| < [`GRAZE_COS`]) where it crosses it;
//! - within a relative [`TANGENT_EPS`] of a sphere's silhouette;
//! - meeting two surfaces within a relative [`TIE_EPS`] of each other (which
//!   one wins is then rounding);
//! - entering a side-choosing selector (rule 1) with a direction whose x in
//!   the selector's space is within [`GRAZE_COS`] of 0.
//!
//! Compared on the rest: the hit flag exactly; where the graph defines
//! which hit ([`super::Graph::which_hit_defined`]), the id exactly, `t` within
//! [`T_REL`] relatively and the hit instance's origin within [`ORIGIN_REL`].

use super::{Geom, Graph, NodeKind, SIZE, Seen, launch_index};
use rt_std::prelude::{Mat4, Vec3};

pub const EDGE_EPS: f32 = 1e-3;
pub const GRAZE_COS: f32 = 1e-3;
pub const TANGENT_EPS: f32 = 2e-3;
pub const TIE_EPS: f32 = 1e-3;
pub const T_REL: f32 = 1e-4;
pub const ORIGIN_REL: f32 = 1e-3;

/// What the comparison of one graph found.
#[derive(Default)]
pub struct Compared {
    pub compared: usize,
    pub hit_only: usize,
    pub skipped: usize,
    pub hits: usize,
    pub mismatches: Vec<String>,
}

/// Every (object-to-world, geometry) leaf of the graph, and the selectors
/// of rule 1 with their object-to-world.
struct Leaves {
    geoms: Vec<(Mat4, usize)>,
    side_selectors: Vec<Mat4>,
}

fn leaves(g: &Graph) -> Leaves {
    let mut l = Leaves { geoms: Vec::new(), side_selectors: Vec::new() };
    fn walk(g: &Graph, n: usize, m: Mat4, l: &mut Leaves) {
        match &g.nodes[n].kind {
            NodeKind::GeometryGroup(insts) => {
                for &i in insts {
                    l.geoms.push((m, g.instances[i].geom));
                }
            }
            NodeKind::Group(c) => c.iter().for_each(|&c| walk(g, c, m, l)),
            NodeKind::Transform(t, c) => walk(g, *c, m * *t, l),
            NodeKind::Selector(rule, c) => {
                if *rule == 1 {
                    l.side_selectors.push(m);
                }
                c.iter().for_each(|&c| walk(g, c, m, l))
            }
        }
    }
    walk(g, g.root(), Mat4::IDENTITY, &mut l);
    l
}

/// Whether the ray is ambiguous for the graph (see the module's doc).
fn ambiguous(g: &Graph, l: &Leaves, o: Vec3, d: Vec3) -> bool {
    for m in &l.side_selectors {
        let dl = m.inverse().transform_vector3(d);
        if (dl.x / dl.length()).abs() < GRAZE_COS {
            return true;
        }
    }
    let mut ts: Vec<f32> = Vec::new();
    for (m, geom) in &l.geoms {
        let inv = m.inverse();
        let (ol, dl) = (inv.transform_point3(o), inv.transform_vector3(d));
        // Distances are measured in the world ray's parameter: `dl` is not
        // normalised, so object-space parameters are world distances.
        match &g.geoms[*geom] {
            Geom::Triangles { positions, indices } => {
                for tri in indices {
                    let [a, b, c] = tri.map(|i| positions[i as usize]);
                    let (e1, e2) = (b - a, c - a);
                    let n = e1.cross(e2);
                    let denom = n.dot(dl);
                    let cos = denom / (n.length() * dl.length());
                    if denom == 0.0 {
                        continue;
                    }
                    let t = n.dot(a - ol) / denom;
                    let p = ol + t * dl;
                    // Barycentrics by areas.
                    let area = n.length_squared();
                    let u = n.dot((p - a).cross(e2)) / area;
                    let v = n.dot(e1.cross(p - a)) / area;
                    let w = 1.0 - u - v;
                    let min = u.min(v).min(w);
                    if t <= 0.0 || min < -EDGE_EPS * 10.0 {
                        continue;
                    }
                    if min.abs() < EDGE_EPS || cos.abs() < GRAZE_COS {
                        return true;
                    }
                    if min > 0.0 {
                        ts.push(t);
                    }
                }
            }
            Geom::Spheres(spheres) => {
                for s in spheres {
                    let a = dl.dot(dl);
                    let lv = s.truncate() - ol;
                    let b = lv.dot(dl) / a;
                    let f = lv - b * dl;
                    let dist = f.length();
                    if (dist / s.w - 1.0).abs() < TANGENT_EPS {
                        return true;
                    }
                    if dist < s.w {
                        let h = ((s.w * s.w - dist * dist) / a).sqrt();
                        ts.extend([b - h, b + h].into_iter().filter(|t| *t > 0.0));
                    }
                }
            }
        }
    }
    ts.sort_by(f32::total_cmp);
    ts.windows(2).any(|w| w[1] - w[0] <= TIE_EPS * w[1].max(1.0))
}

/// Compares `a` (CPU) with `b` (wgpu) for graph `g`.
pub fn compare(g: &Graph, a: &Seen, b: &Seen) -> Compared {
    let l = leaves(g);
    let which = g.which_hit_defined();
    let mut c = Compared::default();
    for i in 0..(SIZE * SIZE) as usize {
        let idx = launch_index(i);
        let (o, d) = g.ray(idx.x, idx.y);
        if ambiguous(g, &l, o, d) {
            c.skipped += 1;
            continue;
        }
        let (x, y) = (a.out[i], b.out[i]);
        let hit = x.x == 1.0;
        c.hits += hit as usize;
        let mut problems = Vec::new();
        if x.x != y.x {
            problems.push("hit flag");
        }
        if which {
            c.compared += 1;
            if x.x == y.x && hit {
                if x.y != y.y {
                    problems.push("hit id");
                }
                if (x.z - y.z).abs() > T_REL * x.z.abs().max(1.0) {
                    problems.push("t");
                }
                let (oa, ob) = (a.origins[i].truncate(), b.origins[i].truncate());
                if (oa - ob).length() > ORIGIN_REL * oa.length().max(1.0) {
                    problems.push("instance origin");
                }
            }
        } else {
            c.hit_only += 1;
            c.compared += 1;
        }
        if !problems.is_empty() {
            c.mismatches.push(format!(
                "launch index {idx} ({}): cpu (hit {}, id {}, t {}, origin {}) wgpu (hit {}, id {}, t {}, origin {}); ray {o} -> {d}",
                problems.join(", "),
                x.x,
                x.y,
                x.z,
                a.origins[i].truncate(),
                y.x,
                y.y,
                y.z,
                b.origins[i].truncate(),
            ));
        }
    }
    c
}
