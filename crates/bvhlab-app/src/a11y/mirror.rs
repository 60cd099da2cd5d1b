//! The page's copy of egui's accessibility tree: it takes AccessKit's tree updates (egui
//! sends one each frame when asked) and says, as a list of [`DomOp`]s, what must change in the
//! page's elements so that they read as the tree does. Only what changed is touched: an
//! element is made once, its attributes and text are set when they differ, its children are
//! put in order when the order differs, and it is removed when its node leaves the tree.
//!
//! The same job as AccessKit's platform adapters (a platform's accessibility objects kept in
//! step with the tree) and as Flutter's web semantics layer (hidden DOM nodes over a canvas),
//! written for this lab: the web side (`web/a11y.rs`) applies the operations, and this half
//! needs no browser, so it is tested natively on the lab's own trees.

use std::collections::{HashMap, HashSet};

use egui::accesskit::{Node, NodeId, Rect, TreeUpdate};

use super::aria::{self, Element, Kind};

/// One change to the page's elements. Nodes are named by their AccessKit id; the element of
/// node `n` has the id `a11y-n` ([`element_id`]).
#[derive(Clone, Debug, PartialEq)]
pub enum DomOp {
    /// Make an element for `node` (not yet in the page: a [`DomOp::Children`] places it).
    Create {
        /// The node.
        node: NodeId,
        /// Its tag.
        tag: &'static str,
    },
    /// Set an attribute (for `value` and `checked` of a form field, the live property too).
    Set {
        /// The node.
        node: NodeId,
        /// The attribute.
        name: &'static str,
        /// Its value.
        value: String,
    },
    /// Remove an attribute.
    Unset {
        /// The node.
        node: NodeId,
        /// The attribute.
        name: &'static str,
    },
    /// Set the element's text (an element with text has no mirrored children).
    Text {
        /// The node.
        node: NodeId,
        /// The text.
        text: String,
    },
    /// Where the element lies over the canvas, in CSS pixels from its mirrored parent's
    /// corner (the root's: from the canvas's): screen magnifiers and touch screen readers
    /// find it where it is drawn.
    Place {
        /// The node.
        node: NodeId,
        /// Left, top, width and height.
        rect: [f64; 4],
    },
    /// The element's children, in order; `None` for the mirror's own container.
    Children {
        /// The parent.
        node: Option<NodeId>,
        /// Its children.
        children: Vec<NodeId>,
    },
    /// Take the element out of the page and forget it.
    Remove {
        /// The node.
        node: NodeId,
    },
    /// egui's keyboard focus moved to this node (`None`: to no widget).
    Focus(Option<NodeId>),
}

/// The element id of a node's element.
pub fn element_id(node: NodeId) -> String {
    format!("a11y-{}", node.0)
}

/// The node an element id names, if it is one of the mirror's.
pub fn node_of(element_id: &str) -> Option<NodeId> {
    element_id
        .strip_prefix("a11y-")
        .and_then(|n| n.parse().ok())
        .map(NodeId)
}

/// What the page shows of one node.
#[derive(Clone, Debug, PartialEq)]
struct Shown {
    element: Element,
    rect: [f64; 4],
    children: Vec<NodeId>,
}

/// The tree as the page shows it, and AccessKit's tree as last updated.
#[derive(Default)]
pub struct Mirror {
    /// AccessKit's nodes, all of them, as the updates left them.
    tree: HashMap<NodeId, Node>,
    root: Option<NodeId>,
    focus: Option<NodeId>,
    /// The mirrored nodes, as their elements were last set.
    shown: HashMap<NodeId, Shown>,
    /// The focus the page was last told of.
    shown_focus: Option<NodeId>,
    /// The node whose element the container holds.
    shown_root: Option<NodeId>,
}

impl Mirror {
    /// An empty mirror: the first update makes every element.
    pub fn new() -> Self {
        Self::default()
    }

    /// Takes in a tree update (AccessKit's rules: the nodes given replace those of the same
    /// id; a node no longer reachable from the root is gone). Cheap: the page is compared
    /// with the tree only in [`changes`](Self::changes).
    pub fn update(&mut self, update: TreeUpdate) {
        if let Some(tree) = &update.tree {
            self.root = Some(tree.root);
        }
        for (id, node) in update.nodes {
            self.tree.insert(id, node);
        }
        self.focus = Some(update.focus);
    }

    /// The changes that make the page read as the tree does now, in the order to apply them
    /// (elements made before they are placed, removed after they left their parent).
    pub fn changes(&mut self) -> Vec<DomOp> {
        let mut ops = Vec::new();
        let mut seen = HashSet::new();
        let mut made = Vec::new();
        let root = self.root.filter(|root| self.tree.contains_key(root));
        if let Some(root) = root {
            self.visit(root, [0.0, 0.0], &mut seen, &mut ops, &mut made);
        }
        if root != self.shown_root || root.is_some_and(|r| made.contains(&r)) {
            self.shown_root = root;
            ops.push(DomOp::Children {
                node: None,
                children: root.into_iter().collect(),
            });
        }
        let gone: Vec<NodeId> = self
            .shown
            .keys()
            .filter(|id| !seen.contains(*id))
            .copied()
            .collect();
        for node in gone {
            self.shown.remove(&node);
            ops.push(DomOp::Remove { node });
        }
        // Nodes no longer reachable are dropped from the copy of the tree too.
        let reachable = self.reachable();
        self.tree.retain(|id, _| reachable.contains(id));
        let focus = self
            .focus
            .filter(|f| Some(*f) != self.root && self.shown.contains_key(f));
        if focus != self.shown_focus {
            self.shown_focus = focus;
            ops.push(DomOp::Focus(focus));
        }
        ops
    }

    /// Mirrors `id` and its subtree; `origin` is the mirrored parent's corner.
    fn visit(
        &mut self,
        id: NodeId,
        origin: [f64; 2],
        seen: &mut HashSet<NodeId>,
        ops: &mut Vec<DomOp>,
        made: &mut Vec<NodeId>,
    ) {
        let Some(node) = self.tree.get(&id) else {
            return;
        };
        seen.insert(id);
        let labelled_by: Vec<String> = node
            .labelled_by()
            .iter()
            .filter(|n| self.tree.contains_key(n))
            .map(|n| element_id(*n))
            .collect();
        let element = aria::element(node, &element_id(id), &labelled_by);
        let bounds = node.bounds().unwrap_or(Rect {
            x0: origin[0],
            y0: origin[1],
            x1: origin[0],
            y1: origin[1],
        });
        let rect = [
            round(bounds.x0 - origin[0]),
            round(bounds.y0 - origin[1]),
            round(bounds.width()),
            round(bounds.height()),
        ];
        let children: Vec<NodeId> = if element.text.is_some() {
            Vec::new()
        } else {
            node.children()
                .iter()
                .copied()
                .filter(|c| {
                    self.tree
                        .get(c)
                        .is_some_and(|n| aria::kind(n.role()) == Kind::Shown)
                })
                .collect()
        };
        let before = self.shown.get(&id);
        let fresh = before.is_none_or(|b| b.element.tag != element.tag);
        if fresh {
            if before.is_some() {
                ops.push(DomOp::Remove { node: id });
            }
            ops.push(DomOp::Create {
                node: id,
                tag: element.tag,
            });
            made.push(id);
        }
        let empty = Element {
            tag: element.tag,
            attrs: Vec::new(),
            text: None,
        };
        let old = if fresh {
            &empty
        } else {
            &before.expect("not fresh").element
        };
        diff_attrs(id, &old.attrs, &element.attrs, ops);
        if element.text != old.text {
            ops.push(DomOp::Text {
                node: id,
                text: element.text.clone().unwrap_or_default(),
            });
        }
        if fresh || before.is_some_and(|b| b.rect != rect) {
            ops.push(DomOp::Place { node: id, rect });
        }
        let old_children = if fresh {
            None
        } else {
            before.map(|b| b.children.clone())
        };
        let corner = [bounds.x0, bounds.y0];
        for &child in &children {
            self.visit(child, corner, seen, ops, made);
        }
        if old_children.as_ref() != Some(&children) || children.iter().any(|c| made.contains(c)) {
            ops.push(DomOp::Children {
                node: Some(id),
                children: children.clone(),
            });
        }
        self.shown.insert(
            id,
            Shown {
                element,
                rect,
                children,
            },
        );
    }

    /// The nodes reachable from the root.
    fn reachable(&self) -> HashSet<NodeId> {
        let mut out = HashSet::new();
        let mut stack: Vec<NodeId> = self.root.into_iter().collect();
        while let Some(id) = stack.pop() {
            if let Some(node) = self.tree.get(&id)
                && out.insert(id)
            {
                stack.extend(node.children().iter().copied());
            }
        }
        out
    }

    /// The node egui's keyboard focus is on, if it is on a widget.
    pub fn focus(&self) -> Option<NodeId> {
        self.focus.filter(|f| Some(*f) != self.root)
    }

    /// Whether a combo box's list is open (Escape then closes it).
    pub fn popup_open(&self) -> bool {
        self.tree
            .values()
            .any(|n| n.role() == egui::accesskit::Role::ComboBox && n.is_expanded() == Some(true))
    }

    /// How many elements the page has.
    pub fn len(&self) -> usize {
        self.shown.len()
    }

    /// Whether the page has no element yet.
    pub fn is_empty(&self) -> bool {
        self.shown.is_empty()
    }
}

/// The attribute changes from `old` to `new` (both sorted by name).
fn diff_attrs(
    node: NodeId,
    old: &[(&'static str, String)],
    new: &[(&'static str, String)],
    ops: &mut Vec<DomOp>,
) {
    for (name, value) in new {
        if old
            .iter()
            .find(|(n, _)| n == name)
            .is_none_or(|(_, v)| v != value)
        {
            ops.push(DomOp::Set {
                node,
                name,
                value: value.clone(),
            });
        }
    }
    for (name, _) in old {
        if !new.iter().any(|(n, _)| n == name) {
            ops.push(DomOp::Unset { node, name });
        }
    }
}

/// CSS pixels to a tenth: finer moves are not worth a style change.
fn round(x: f64) -> f64 {
    (x * 10.0).round() / 10.0
}
