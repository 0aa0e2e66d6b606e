//! From obvhs's BVH2 to the 8-wide layout, by the surface area heuristic:
//! which BVH2 nodes become a wide node's children, and which subtrees of
//! at most [`PACKET`] primitives become leaves, is chosen by dynamic
//! programming over the BVH2 (Ylitie, Karras and Laine, HPG 2017, as
//! obvhs's CWBVH conversion does), with a leaf's cost one packet test
//! whatever its fill. Child boxes are the BVH2's exact float boxes.

use super::{LEAF, Node, PACKET, Packet, WIDTH, WideBvh, leaf_ref};
use glam::Vec3;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;

/// Collapses `bvh` (non-empty). `triangle(p)` gives primitive `p`'s
/// vertices when every primitive is a triangle (the leaves then get
/// packets).
pub(crate) fn collapse(bvh: &Bvh2, triangle: Option<&(dyn Fn(u32) -> [Vec3; 3] + Sync)>) -> WideBvh {
    let counts = subtree_counts(bvh);
    let mut out = Out {
        bvh,
        triangle,
        tree: WideBvh { nodes: Vec::new(), packets: Vec::new(), slots: Vec::new(), root: 0, depth: 1 },
    };
    if bvh.nodes.is_empty() {
        out.tree.root = LEAF; // never walked: callers skip empty groups
        return out.tree;
    }
    if counts[0] as usize <= PACKET {
        out.tree.root = out.leaf(0);
        return out.tree;
    }
    let plan = Plan::new(bvh, &counts);
    // (BVH2 node, wide node, its depth).
    let mut work = vec![(0u32, 0u32, 1u32)];
    out.tree.nodes.push(Node::EMPTY);
    let mut children = Vec::with_capacity(WIDTH);
    while let Some((n, w, depth)) = work.pop() {
        out.tree.depth = out.tree.depth.max(depth + 1);
        let node = &bvh.nodes[n as usize];
        if node.is_leaf() {
            // A BVH2 leaf of more than PACKET primitives: leaves of PACKET
            // under this node, the last child continuing the chain.
            out.chain(w, n, depth);
            continue;
        }
        children.clear();
        plan.children(n, &mut children);
        for (slot, &c) in children.iter().enumerate() {
            let child_ref = if plan.is_leaf(c) {
                out.leaf(c)
            } else {
                let index = out.tree.nodes.len() as u32;
                out.tree.nodes.push(Node::EMPTY);
                work.push((c, index, depth + 1));
                index
            };
            set_child(&mut out.tree.nodes[w as usize], slot, bvh.nodes[c as usize].aabb(), child_ref);
        }
    }
    out.tree
}

/// The cost of testing a node's eight boxes, and a leaf's packet, per
/// unit of surface area (relative: only their ratio matters).
const NODE_COST: f32 = 1.0;
const PACKET_COST: f32 = 1.0;

/// The collapse's choices for every BVH2 node `n`, from `cost[n][i - 1]`,
/// the least cost of the subtree as at most `i` children of a wide node:
/// `split[n][i - 1]` says how (0: as one child, a leaf if `leaf[n]`, else
/// a wide node of its own; else `k`, the left child's subtree taking `k`
/// of the `i` slots and the right one's the rest), and `node_split[n]` is
/// the split of the eight slots when `n` is a wide node.
struct Plan<'a> {
    bvh: &'a Bvh2,
    split: Vec<[u8; WIDTH]>,
    node_split: Vec<u8>,
    leaf: Vec<bool>,
}

impl<'a> Plan<'a> {
    fn new(bvh: &'a Bvh2, counts: &[u32]) -> Plan<'a> {
        let n = bvh.nodes.len();
        let mut cost = vec![[0f32; WIDTH]; n];
        let mut split = vec![[0u8; WIDTH]; n];
        let mut leaf = vec![false; n];
        let mut node_split = vec![0u8; n];
        for m in children_first(bvh) {
            let node = &bvh.nodes[m as usize];
            let a = area(node.aabb());
            let count = counts[m as usize] as usize;
            let as_leaf = if count <= PACKET { a * PACKET_COST } else { f32::INFINITY };
            if node.is_leaf() {
                // (More than PACKET primitives: a chain of leaves, see
                // `Out::chain`; as costly as a node per slot here.)
                let c = if count <= PACKET {
                    as_leaf
                } else {
                    a * (NODE_COST + PACKET_COST * count.div_ceil(PACKET) as f32)
                };
                cost[m as usize] = [c; WIDTH];
                leaf[m as usize] = count <= PACKET;
                continue;
            }
            let (l, r) = (node.first_index as usize, node.first_index as usize + 1);
            // The best way to spread the two subtrees over `j` slots.
            let distribute = |j: usize| {
                (1..j).map(|k| (cost[l][k - 1] + cost[r][j - k - 1], k as u8)).min_by(|x, y| x.0.total_cmp(&y.0))
            };
            let (best8, k8) = distribute(WIDTH).expect("two slots at least");
            node_split[m as usize] = k8;
            let as_node = a * NODE_COST + best8;
            let mut row = [0f32; WIDTH];
            let mut how = [0u8; WIDTH];
            (row[0], leaf[m as usize]) = if as_leaf <= as_node { (as_leaf, true) } else { (as_node, false) };
            for j in 2..=WIDTH {
                let (c, k) = distribute(j).expect("two slots at least");
                (row[j - 1], how[j - 1]) = if c < row[j - 2] { (c, k) } else { (row[j - 2], how[j - 2]) };
            }
            cost[m as usize] = row;
            split[m as usize] = how;
        }
        Plan { bvh, split, node_split, leaf }
    }

    /// Whether BVH2 node `n`, as one child, is a leaf.
    fn is_leaf(&self, n: u32) -> bool {
        self.leaf[n as usize]
    }

    /// The BVH2 nodes that are the children of the wide node made of
    /// BVH2 node `n` (an inner node, not a leaf).
    fn children(&self, n: u32, out: &mut Vec<u32>) {
        let node = &self.bvh.nodes[n as usize];
        let (l, r) = (node.first_index, node.first_index + 1);
        let k = self.node_split[n as usize] as usize;
        self.spread(l, k, out);
        self.spread(r, WIDTH - k, out);
    }

    /// Subtree `n` as at most `slots` children.
    fn spread(&self, n: u32, slots: usize, out: &mut Vec<u32>) {
        let node = &self.bvh.nodes[n as usize];
        let mut i = slots;
        while i > 1 && self.split[n as usize][i - 1] == 0 {
            i -= 1;
        }
        if i == 1 || node.is_leaf() {
            out.push(n);
            return;
        }
        let k = self.split[n as usize][i - 1] as usize;
        self.spread(node.first_index, k, out);
        self.spread(node.first_index + 1, i - k, out);
    }
}

/// BVH2 nodes, each after its children.
fn children_first(bvh: &Bvh2) -> Vec<u32> {
    let mut order = Vec::with_capacity(bvh.nodes.len());
    let mut stack = vec![0u32];
    while let Some(n) = stack.pop() {
        order.push(n);
        let node = &bvh.nodes[n as usize];
        if !node.is_leaf() {
            stack.extend([node.first_index, node.first_index + 1]);
        }
    }
    order.reverse();
    order
}

struct Out<'a> {
    bvh: &'a Bvh2,
    triangle: Option<&'a (dyn Fn(u32) -> [Vec3; 3] + Sync)>,
    tree: WideBvh,
}

impl Out<'_> {
    /// A leaf holding the primitives under BVH2 node `n` (at most PACKET).
    fn leaf(&mut self, n: u32) -> u32 {
        let mut prims = [u32::MAX; PACKET];
        let mut count = 0;
        let mut stack = vec![n];
        while let Some(m) = stack.pop() {
            let node = &self.bvh.nodes[m as usize];
            if node.is_leaf() {
                for i in node.first_index..node.first_index + node.prim_count {
                    prims[count] = self.bvh.primitive_indices[i as usize];
                    count += 1;
                }
            } else {
                stack.extend([node.first_index + 1, node.first_index]);
            }
        }
        self.push_leaf(&prims[..count])
    }

    fn push_leaf(&mut self, prims: &[u32]) -> u32 {
        let index = (self.tree.slots.len() / PACKET) as u32;
        let mut slots = [u32::MAX; PACKET];
        slots[..prims.len()].copy_from_slice(prims);
        self.tree.slots.extend(slots);
        if let Some(triangle) = self.triangle {
            let mut packet = Packet::EMPTY;
            for (lane, &p) in prims.iter().enumerate() {
                for (k, v) in triangle(p).iter().enumerate() {
                    packet.v[3 * k][lane] = v.x;
                    packet.v[3 * k + 1][lane] = v.y;
                    packet.v[3 * k + 2][lane] = v.z;
                }
            }
            self.tree.packets.push(packet);
        }
        leaf_ref(index, prims.len() as u32)
    }

    /// Wide node `w` over BVH2 leaf `n`'s primitives: up to seven leaves
    /// and, for the rest, a child node of the same box that continues.
    fn chain(&mut self, w: u32, n: u32, depth: u32) {
        let node = self.bvh.nodes[n as usize];
        let prims: Vec<u32> = self.bvh.primitive_indices
            [node.first_index as usize..(node.first_index + node.prim_count) as usize]
            .to_vec();
        let mut w = w;
        let mut rest = &prims[..];
        let mut depth = depth;
        loop {
            let fits = rest.len() <= WIDTH * PACKET;
            let leaves = if fits { rest.len().div_ceil(PACKET) } else { WIDTH - 1 };
            for slot in 0..leaves {
                let chunk = &rest[slot * PACKET..((slot + 1) * PACKET).min(rest.len())];
                let r = self.push_leaf(chunk);
                set_child(&mut self.tree.nodes[w as usize], slot, node.aabb(), r);
            }
            if fits {
                break;
            }
            rest = &rest[leaves * PACKET..];
            let next = self.tree.nodes.len() as u32;
            self.tree.nodes.push(Node::EMPTY);
            set_child(&mut self.tree.nodes[w as usize], WIDTH - 1, node.aabb(), next);
            w = next;
            depth += 1;
            self.tree.depth = self.tree.depth.max(depth + 1);
        }
    }
}

fn set_child(node: &mut Node, slot: usize, b: &Aabb, r: u32) {
    let (lo, hi) = (b.min, b.max);
    for (axis, (l, h)) in [(lo.x, hi.x), (lo.y, hi.y), (lo.z, hi.z)].into_iter().enumerate() {
        node.planes[2 * axis][slot] = l;
        node.planes[2 * axis + 1][slot] = h;
    }
    node.child[slot] = r;
}

/// Half the surface area of `b` (what the collapse compares).
fn area(b: &Aabb) -> f32 {
    let d = (b.max - b.min).max(glam::Vec3A::ZERO);
    d.x * d.y + d.y * d.z + d.z * d.x
}

/// Primitives under each BVH2 node.
fn subtree_counts(bvh: &Bvh2) -> Vec<u32> {
    let mut counts = vec![0u32; bvh.nodes.len()];
    if bvh.nodes.is_empty() {
        return counts;
    }
    for n in children_first(bvh) {
        let node = &bvh.nodes[n as usize];
        counts[n as usize] = if node.is_leaf() {
            node.prim_count
        } else {
            counts[node.first_index as usize] + counts[node.first_index as usize + 1]
        };
    }
    counts
}
