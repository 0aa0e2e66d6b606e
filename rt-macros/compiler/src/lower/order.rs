//! One dependency sort for everything a unit lowers in dependency order:
//! constants (a value may name other constants), structs (a field may be
//! another struct) and helpers (callees before callers).
//!
//! [`Order::visit`] walks depth first from a root, dependencies in the order
//! the [`Graph`] gives them, and appends each node once all it depends on is
//! done. What a cycle means is the graph's to say: an error (a struct that
//! contains itself, recursion) or nothing (constants, whose cycle the
//! lowering of their values reports).

use std::collections::HashSet;
use std::hash::Hash;

/// A node's dependencies, each with what its edge carries.
pub type Deps<G> = Vec<(<G as Graph>::Node, <G as Graph>::Edge)>;

/// What the sort needs to know of a graph.
pub trait Graph {
    type Node: Clone + Eq + Hash;
    /// What a dependency carries (the span of a call), for the cycle error.
    type Edge;
    type Error;

    /// The nodes `n` depends on, in the order to visit them, or why `n`
    /// cannot be ordered (which stops the walk). Asked each time `n` is
    /// entered.
    fn deps(&mut self, n: &Self::Node) -> Result<Deps<Self>, Self::Error>;

    /// `n`'s dependencies are done; an error stops the walk before `n`
    /// joins the order.
    fn done(&mut self, _n: &Self::Node) -> Result<(), Self::Error> {
        Ok(())
    }

    /// `from` depends on `to`, which is on the path being walked: the
    /// error to stop with, or `None` to skip that dependency.
    fn cycle(&mut self, from: &Self::Node, to: &Self::Node, edge: &Self::Edge) -> Option<Self::Error>;
}

/// Nodes in dependency order, built by one or more walks.
pub struct Order<N> {
    done: HashSet<N>,
    /// Every node after the nodes it depends on.
    pub nodes: Vec<N>,
}

impl<N: Clone + Eq + Hash> Order<N> {
    pub fn new() -> Self {
        Order { done: HashSet::new(), nodes: Vec::new() }
    }

    /// Orders `root` and, before it, everything it depends on that is not
    /// ordered yet. A walk stopped by an error keeps the nodes it finished;
    /// those on its path are walked afresh when a later walk reaches them.
    pub fn visit<G: Graph<Node = N>>(&mut self, graph: &mut G, root: &N) -> Result<(), G::Error> {
        self.walk(graph, root, &mut Vec::new())
    }

    fn walk<G: Graph<Node = N>>(&mut self, graph: &mut G, n: &N, path: &mut Vec<N>) -> Result<(), G::Error> {
        if self.done.contains(n) {
            return Ok(());
        }
        path.push(n.clone());
        for (d, edge) in graph.deps(n)? {
            if path.contains(&d) {
                match graph.cycle(n, &d, &edge) {
                    Some(e) => return Err(e),
                    None => continue,
                }
            }
            self.walk(graph, &d, path)?;
        }
        graph.done(n)?;
        path.pop();
        self.done.insert(n.clone());
        self.nodes.push(n.clone());
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    struct G(HashMap<u32, Vec<u32>>, bool);

    impl Graph for G {
        type Node = u32;
        type Edge = ();
        type Error = (u32, u32);
        fn deps(&mut self, n: &u32) -> Result<Vec<(u32, ())>, (u32, u32)> {
            Ok(self.0.get(n).into_iter().flatten().map(|d| (*d, ())).collect())
        }
        fn cycle(&mut self, from: &u32, to: &u32, _: &()) -> Option<(u32, u32)> {
            self.1.then_some((*from, *to))
        }
    }

    #[test]
    fn dependencies_first_in_given_order() {
        let mut g = G(HashMap::from([(1, vec![3, 2]), (2, vec![3]), (4, vec![1])]), true);
        let mut o = Order::new();
        for r in [1, 4, 2] {
            o.visit(&mut g, &r).unwrap();
        }
        assert_eq!(o.nodes, vec![3, 2, 1, 4]);
    }

    #[test]
    fn cycles_stop_or_are_skipped() {
        let mut g = G(HashMap::from([(1, vec![2]), (2, vec![1])]), true);
        assert_eq!(Order::new().visit(&mut g, &1), Err((2, 1)));
        g.1 = false;
        let mut o = Order::new();
        o.visit(&mut g, &1).unwrap();
        assert_eq!(o.nodes, vec![2, 1]);
    }
}
