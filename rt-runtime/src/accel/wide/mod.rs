//! The CPU backend's tree: each geometry group's BVH2 collapsed into 8-wide
//! nodes with float child bounds in SoA, and leaves of up to four triangles
//! in SoA, walked with SIMD box and triangle tests (Embree's BVH8 +
//! Triangle4 layout; obvhs keeps building the BVH2 it comes from).
//!
//! A node's eight child boxes are six rows of eight floats (`lo_x`, `hi_x`,
//! `lo_y`, ...), so one ray is tested against all eight boxes in six
//! subtractions, six products and a few min/max (one AVX2 instruction
//! each). A leaf's four triangles are nine rows of four floats (the three
//! vertices' coordinates), tested in one four-wide watertight test that
//! gives exactly the hits of `watertight::WatertightRay::intersect`, bit
//! for bit: same operations, same order, no fused multiply-adds.
//!
//! Files: `collapse` builds the layout from a BVH2; `walk` is the
//! ordered traversal, generic over `kernels` (the box and triangle tests
//! of each instruction set) and dispatched by [`isa`] (run-time detection,
//! `RT_CPU_SIMD` to force one); `watertight` is the one-triangle test
//! the packet test reproduces; `packet_walk` walks 16 rays together (the
//! measurement of what ray packets gain on this tree: `rt-bench`'s
//! `cpu_packet_walk_vs_walk`).

pub(crate) mod collapse;
pub mod isa;
pub(crate) mod kernels;
pub(crate) mod packet_walk;
#[doc(hidden)]
pub mod testing;
#[cfg(test)]
mod tests;
pub(crate) mod walk;
pub(crate) mod watertight;

/// Children per node.
pub(crate) const WIDTH: usize = 8;
/// Triangles per leaf (one packet).
pub(crate) const PACKET: usize = 4;

/// A child reference with this bit set is a leaf: bits 29-30 hold its
/// primitive count less one, bits 0-28 its index (into
/// [`WideBvh::packets`] and, four per leaf, [`WideBvh::slots`]). Without
/// it, a node index.
pub(crate) const LEAF: u32 = 1 << 31;
const LEAF_INDEX: u32 = (1 << 29) - 1;

/// A leaf's child reference.
pub(crate) fn leaf_ref(index: u32, count: u32) -> u32 {
    debug_assert!((1..=PACKET as u32).contains(&count) && index <= LEAF_INDEX);
    LEAF | ((count - 1) << 29) | index
}

/// A leaf reference's (index, primitive count).
#[inline(always)]
pub(crate) fn leaf_of(r: u32) -> (u32, u32) {
    (r & LEAF_INDEX, ((r >> 29) & 3) + 1)
}

/// One 8-wide node. `planes` holds the children's boxes by row: `lo_x`,
/// `hi_x`, `lo_y`, `hi_y`, `lo_z`, `hi_z`; an unused child has the empty
/// box (`lo` +inf, `hi` -inf), which no ray enters.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(crate) struct Node {
    pub(crate) planes: [[f32; WIDTH]; 6],
    pub(crate) child: [u32; WIDTH],
}

impl Node {
    pub(crate) const EMPTY: Node = Node {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [u32::MAX; WIDTH],
    };
}

/// One leaf's triangles by row: `a.x`, `a.y`, `a.z`, `b.x`, ... `c.z`, one
/// triangle a lane. Unused lanes hold NaN vertices, which never hit.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub(crate) struct Packet {
    pub(crate) v: [[f32; PACKET]; 9],
}

impl Packet {
    pub(crate) const EMPTY: Packet = Packet { v: [[f32::NAN; PACKET]; 9] };

    /// Lane `lane`'s vertices.
    #[inline(always)]
    pub(crate) fn vertices(&self, lane: usize) -> [glam::Vec3; 3] {
        // (Written out: `array::map` here did not inline, and cost a third
        // of the CPU backend's per-hit callback.)
        let v = &self.v;
        let lane = lane & (PACKET - 1);
        let vertex = |k: usize| glam::Vec3::new(v[k][lane], v[k + 1][lane], v[k + 2][lane]);
        [vertex(0), vertex(3), vertex(6)]
    }
}

/// A geometry group's tree in the CPU backend's layout.
pub(crate) struct WideBvh {
    pub(crate) nodes: Vec<Node>,
    /// Each leaf's triangles (empty unless every primitive is a triangle).
    pub(crate) packets: Vec<Packet>,
    /// Each leaf's primitives, [`PACKET`] a leaf (indices into the group's
    /// `prims`; `u32::MAX` past the leaf's count).
    pub(crate) slots: Vec<u32>,
    /// Where the walk starts: node 0, or the only leaf of a small group.
    pub(crate) root: u32,
    /// The most nodes on a path from the root to a leaf (the walk's stack
    /// holds at most `7 * depth + 1` entries).
    pub(crate) depth: u32,
}

impl WideBvh {
    /// Whether leaves are triangle packets (else the walk hands each
    /// leaf's primitives to the caller).
    pub(crate) fn has_packets(&self) -> bool {
        !self.packets.is_empty()
    }
}
