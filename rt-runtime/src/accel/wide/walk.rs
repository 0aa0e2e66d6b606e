//! The ordered walk of a [`WideBvh`]: test a node's eight boxes at once,
//! go on into the nearest child entered and push the others far to near,
//! pop entries the closest hit so far has passed without testing them.

use super::kernels::{Hits, Kernels, WalkRay};
use super::{LEAF, WIDTH, WideBvh};
use std::mem::MaybeUninit;

/// A pushed child: its reference and entry distance.
pub(crate) type Entry = (u32, f32);

/// Stack entries a walk of `tree` may need.
pub(crate) fn stack_len(tree: &WideBvh) -> usize {
    (WIDTH - 1) * tree.depth as usize + 1
}

/// Walks `tree` with `ray` up to `tmax`. Each leaf the ray enters goes to
/// `leaf` with its reference: with its triangle hits when the tree has
/// packets (only leaves with a hit), else with None for the caller to test
/// its primitives. `leaf` returns the new `tmax` (the closest hit so far),
/// or None to stop. `stack` holds at least [`stack_len`] entries.
#[inline(always)]
pub(crate) fn walk<K: Kernels, F: FnMut(u32, Option<&Hits>) -> Option<f32>>(
    tree: &WideBvh,
    ray: &WalkRay,
    tmax: f32,
    stack: &mut [MaybeUninit<Entry>],
    leaf: F,
) {
    walk_from::<K, F>(tree, tree.root, ray, tmax, stack, leaf)
}

/// [`walk`] from the node or leaf `start` of `tree` (the packet walk
/// hands a subtree on to single rays).
#[inline(always)]
pub(crate) fn walk_from<K: Kernels, F: FnMut(u32, Option<&Hits>) -> Option<f32>>(
    tree: &WideBvh,
    start: u32,
    ray: &WalkRay,
    mut tmax: f32,
    stack: &mut [MaybeUninit<Entry>],
    mut leaf: F,
) {
    let packets = tree.has_packets();
    if packets && ray.triangle.is_none() {
        return;
    }
    let k = K::ray(ray);
    let mut sp = 0usize;
    let mut current = start;
    loop {
        if current & LEAF == 0 {
            debug_assert!((current as usize) < tree.nodes.len());
            // SAFETY: child references are built by `collapse`, each naming a
            // node it pushed.
            let node = unsafe { tree.nodes.get_unchecked(current as usize) };
            let (mut mask, tnear) = K::node(node, &k, tmax);
            if mask != 0 {
                // (`& 7`: the mask has eight bits, which the compiler cannot
                // see, so indexing by it would be bounds-checked.)
                let first = mask.trailing_zeros() as usize & 7;
                mask &= mask - 1;
                if mask == 0 {
                    current = node.child[first];
                    continue;
                }
                // Two or more: nearest last, so it is the one taken.
                let mut hit: [Entry; WIDTH] = [(0, 0.0); WIDTH];
                hit[0] = (node.child[first], tnear[first]);
                let mut n = 1;
                while mask != 0 {
                    let i = mask.trailing_zeros() as usize & 7;
                    mask &= mask - 1;
                    let e = (node.child[i], tnear[i]);
                    // Insertion by descending distance.
                    let mut j = n;
                    while j > 0 && hit[j - 1].1 < e.1 {
                        hit[j] = hit[j - 1];
                        j -= 1;
                    }
                    hit[j] = e;
                    n += 1;
                }
                debug_assert!(sp + n - 1 <= stack.len());
                for e in &hit[..n - 1] {
                    // SAFETY: the stack holds `stack_len(tree)` entries, which
                    // bounds the pushes along any path.
                    unsafe { stack.get_unchecked_mut(sp).write(*e) };
                    sp += 1;
                }
                current = hit[n - 1].0;
                continue;
            }
        } else if packets {
            let (index, _) = super::leaf_of(current);
            debug_assert!((index as usize) < tree.packets.len());
            // SAFETY: leaf references are built by `collapse`, each naming a
            // leaf it pushed (with a packet, in trees that have packets).
            let hits = K::packet(unsafe { tree.packets.get_unchecked(index as usize) }, &k, tmax);
            if hits.mask != 0 {
                match leaf(current, Some(&hits)) {
                    Some(t) => tmax = t,
                    None => return,
                }
            }
        } else {
            match leaf(current, None) {
                Some(t) => tmax = t,
                None => return,
            }
        }
        // The next entry the closest hit has not passed.
        loop {
            if sp == 0 {
                return;
            }
            sp -= 1;
            // SAFETY: entries below `sp` were written above.
            let (r, t) = unsafe { stack.get_unchecked(sp).assume_init() };
            if t <= tmax {
                current = r;
                break;
            }
        }
    }
}
