//! After the walk: `<ref>`s → node indices (so forward references work), cycle detection,
//! then the shared [`SceneObject`] tree built bottom-up (`src/core/parser.cpp::
//! transform_resolve`, `check_cycles`). Iterative, so a long reference chain cannot
//! overflow the stack.

use std::cell::Cell;
use std::rc::Rc;

use super::object::{Child, SceneObject};
use super::raw::{RawNode, RawScene, Target};
use crate::error::SceneError;

/// A node as named in a cycle message: its id, else `<tag type="plugin">`.
fn label(n: &RawNode) -> String {
    match &n.id {
        Some(id) => id.clone(),
        None => format!("<{} type=\"{}\">", n.tag, n.plugin),
    }
}

/// Child indices of every node, `<ref>`s resolved through the id map (aliases included).
fn resolve_refs(scene: &RawScene) -> Result<Vec<Vec<usize>>, SceneError> {
    let mut edges = Vec::with_capacity(scene.nodes.len());
    for n in &scene.nodes {
        let mut e = Vec::with_capacity(n.children.len());
        for c in &n.children {
            e.push(match &c.target {
                Target::Node(i) => *i,
                Target::Ref(id) => match scene.ids.get(id) {
                    Some(&(i, _)) => i,
                    None => {
                        return Err(SceneError::at(
                            &c.pos,
                            format!("unresolved reference to \"{id}\": no object has id=\"{id}\""),
                        ));
                    }
                },
            });
        }
        edges.push(e);
    }
    Ok(edges)
}

/// Nodes in post-order from the root (children before parents); a cycle is an error.
fn post_order(scene: &RawScene, edges: &[Vec<usize>]) -> Result<Vec<usize>, SceneError> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    let mut mark = vec![Mark::New; scene.nodes.len()];
    let mut order = Vec::with_capacity(scene.nodes.len());
    // (node, index of the next child to visit)
    let mut stack: Vec<(usize, usize)> = vec![(0, 0)];
    mark[0] = Mark::Open;
    while let Some(top) = stack.last_mut() {
        let (node, next) = *top;
        if next == edges[node].len() {
            mark[node] = Mark::Done;
            order.push(node);
            stack.pop();
            continue;
        }
        top.1 += 1;
        let child = edges[node][next];
        match mark[child] {
            Mark::Done => {}
            Mark::New => {
                mark[child] = Mark::Open;
                stack.push((child, 0));
            }
            Mark::Open => {
                let from = stack.iter().position(|&(n, _)| n == child).unwrap_or(0);
                let mut names: Vec<String> = stack[from..].iter().map(|&(n, _)| label(&scene.nodes[n])).collect();
                names.push(label(&scene.nodes[child]));
                return Err(SceneError::at(
                    &scene.nodes[node].children[next].pos,
                    format!("circular reference: {}", names.join(" -> ")),
                ));
            }
        }
    }
    Ok(order)
}

/// The root object of the resolved, shared tree.
pub(crate) fn build_tree(scene: RawScene) -> Result<Rc<SceneObject>, SceneError> {
    let edges = resolve_refs(&scene)?;
    let search_paths = scene.search_paths.clone();
    let order = post_order(&scene, &edges)?;
    let mut raw: Vec<Option<RawNode>> = scene.nodes.into_iter().map(Some).collect();
    let mut built: Vec<Option<Rc<SceneObject>>> = vec![None; raw.len()];
    for i in order {
        let Some(n) = raw[i].take() else { continue };
        let children = n
            .children
            .into_iter()
            .zip(&edges[i])
            .map(|(c, &target)| Child {
                name: c.name,
                // Post-order: every child was built before its parent.
                object: built[target].clone().expect("child built before parent"),
                pos: c.pos,
                used: Cell::new(false),
            })
            .collect();
        built[i] = Some(Rc::new(SceneObject {
            tag: n.tag,
            plugin: n.plugin,
            id: n.id,
            pos: n.pos,
            properties: n.properties,
            children,
            search_paths: if i == 0 { search_paths.clone() } else { Vec::new() },
        }));
    }
    Ok(built[0].take().expect("the root is last in post-order"))
}
