//! The node graph is a forest, as the specification requires: a node has
//! at most one parent, no node is its own ancestor, and a scene lists
//! root nodes, each once. Without this check a file whose nodes share
//! children is expanded once per path, exponentially in its depth.

use crate::error::GltfError;
use crate::gltf::Reader;
use gltf::json;

pub(super) fn check(r: &Reader, root: &json::Root) -> Result<(), GltfError> {
    let n = root.nodes.len();
    let mut parent: Vec<Option<usize>> = vec![None; n];
    for (i, node) in root.nodes.iter().enumerate() {
        for child in node.children.iter().flatten() {
            let c = child.value();
            if c == i {
                return Err(r.error(&format!("nodes[{i}]"), "lists itself as a child".into()));
            }
            if let Some(p) = parent[c].replace(i) {
                let problem = if p == i {
                    format!("lists nodes[{c}] twice as a child")
                } else {
                    format!("is a second parent of nodes[{c}], a child of nodes[{p}] already (a node has one parent)")
                };
                return Err(r.error(&format!("nodes[{i}]"), problem));
            }
        }
    }
    // Walk up from every node; a walk that meets itself is a cycle.
    const UNSEEN: u8 = 0;
    const ON_PATH: u8 = 1;
    const DONE: u8 = 2;
    let mut state = vec![UNSEEN; n];
    let mut path = Vec::new();
    for start in 0..n {
        let mut at = Some(start);
        while let Some(i) = at {
            match state[i] {
                DONE => break,
                ON_PATH => {
                    return Err(
                        r.error(&format!("nodes[{i}]"), "is its own ancestor (the node graph has a cycle)".into())
                    );
                }
                _ => {
                    state[i] = ON_PATH;
                    path.push(i);
                    at = parent[i];
                }
            }
        }
        for i in path.drain(..) {
            state[i] = DONE;
        }
    }
    for (s, scene) in root.scenes.iter().enumerate() {
        let mut listed = vec![false; n];
        for node in &scene.nodes {
            let i = node.value();
            if let Some(p) = parent[i] {
                return Err(r.error(
                    &format!("scenes[{s}]"),
                    format!("lists nodes[{i}], which is a child of nodes[{p}] (a scene lists root nodes)"),
                ));
            }
            if std::mem::replace(&mut listed[i], true) {
                return Err(r.error(&format!("scenes[{s}]"), format!("lists nodes[{i}] twice")));
            }
        }
    }
    Ok(())
}
