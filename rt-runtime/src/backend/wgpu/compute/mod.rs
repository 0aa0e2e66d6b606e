//! The compute traversal: the scene encoded into words ([`super::encode`])
//! walked by the kernel's own WGSL
//! (`traverse.wgsl`, `graph.wgsl`, linked by [`super::kernel`]).
//!
//! Traversal: every transform chain down to a geometry group is flattened
//! into an instance (one matrix, its inverse, the AND of the chain's
//! visibility masks). A group of instances is the two-level fast path
//! (`rt_search` in traverse.wgsl). Anything deeper — groups of groups,
//! transforms above groups or selectors, selectors — gets a node-table entry
//! that the graph traversal (graph.wgsl) walks with one explicit stack of
//! graph nodes and BVH nodes, keeping a small array of transform levels
//! instead of recursing; selectors call the generated `rt_visit_dispatch`.
//! The graph traversal is linked only into kernels whose scene needs it, so
//! two-level scenes keep the lean kernel. Semantics are the CPU backend's.
//!
