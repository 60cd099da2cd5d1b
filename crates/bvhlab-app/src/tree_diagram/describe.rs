//! The words a hovered node's tooltip shows: what it is, where it is, what the query did.

use std::fmt::Write as _;

use bvhlab::{NodeOutline, NodeShape, Vector};

use crate::model::dimension::plural;
use crate::model::outcome::NodeMark;

/// Several lines about `node`: id and depth, leaf or inner, its shape, and what the query
/// (`mark`) or the build playback (`exists`) says about it.
pub(super) fn describe<V: Vector>(
    node: &NodeOutline<V>,
    depth: u32,
    mark: Option<NodeMark>,
    exists: bool,
) -> String {
    let mut text = format!("node {}, depth {depth}\n", node.id.0);
    if node.is_leaf() {
        let n = node.primitives.len();
        let _ = writeln!(text, "leaf, {n} primitive{}", plural(n));
    } else {
        let n = node.children.len();
        let _ = writeln!(
            text,
            "inner node, {n} child{}",
            if n == 1 { "" } else { "ren" }
        );
    }
    text.push_str(&shape_text(&node.shape));
    match mark {
        Some(NodeMark::Visited) => text.push_str("\nthe query went in"),
        Some(NodeMark::Culled) => text.push_str("\nculled: the query missed its region"),
        Some(NodeMark::Pruned) => text.push_str("\npruned: nothing in it can beat the best so far"),
        None => {}
    }
    if !exists {
        text.push_str("\nnot built yet");
    }
    text
}

/// A node's shape in numbers.
fn shape_text<V: Vector>(shape: &NodeShape<V>) -> String {
    let p = |v: V| {
        let coords: Vec<String> = (0..V::DIM).map(|i| format!("{:.3}", v.coord(i))).collect();
        format!("({})", coords.join(", "))
    };
    let round = if V::DIM == 3 { "sphere" } else { "circle" };
    match shape {
        NodeShape::Aabb(b) => format!("AABB min {}, max {}", p(b.min), p(b.max)),
        NodeShape::Sphere(s) => format!("{round} centre {}, radius {:.3}", p(s.center), s.radius),
        NodeShape::Obb(o) => {
            let axes: Vec<String> = o.axes.as_ref().iter().map(|&a| p(a)).collect();
            format!(
                "OBB centre {}, half extents {}, axes {}",
                p(o.center),
                p(o.half_extents),
                axes.join(", ")
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhlab::glam::Vec2;
    use bvhlab::{Aabb2, NodeId, Sphere2};

    #[test]
    fn says_leaf_or_inner_and_the_shape() {
        let mut node = NodeOutline {
            id: NodeId(7),
            parent: None,
            depth: 3,
            shape: NodeShape::Aabb(Aabb2::new(Vec2::new(1.0, 2.0), Vec2::new(3.5, 4.0))),
            splits: Vec::new(),
            children: Vec::new(),
            primitives: vec![4, 9],
        };
        let text = describe(&node, 3, Some(NodeMark::Culled), true);
        assert!(
            text.starts_with("node 7, depth 3\nleaf, 2 primitives\n"),
            "{text}"
        );
        assert!(
            text.contains("AABB min (1.000, 2.000), max (3.500, 4.000)"),
            "{text}"
        );
        assert!(text.contains("culled"), "{text}");
        node.children = vec![NodeId(8)];
        node.shape = NodeShape::Sphere(Sphere2::new(Vec2::new(0.5, -1.0), 2.0));
        let text = describe(&node, 3, None, false);
        assert!(text.contains("inner node, 1 child\n"), "{text}");
        assert!(
            text.contains("circle centre (0.500, -1.000), radius 2.000"),
            "{text}"
        );
        assert!(text.ends_with("not built yet"), "{text}");
    }
}
