//! What the 3D view shows, as a list of segments, polygons, markers and highlighted
//! triangles: the structure's level, the nodes the query visited, culled and pruned (or a
//! build's nodes so far), the ray with its hit point and normal, the query point with its
//! closest points, the node hovered (in the tree diagram or on the mesh) with its triangles,
//! and the gizmo. Read from the playback snapshot, as the 2D canvas is.

use bvhlab::glam::Vec3;
use bvhlab::structure::PrimitiveResult;
use bvhlab::{NodeId, Primitive, Triangle3};
use egui::Color32;

use super::input::Handle;
use super::wire::{self, Segment};
use crate::model::build_job::Structure;
use crate::model::lab3d::Lab3d;
use crate::model::lane::Lane;
use crate::model::outcome::NodeMark;
use crate::model::predict::About;
use crate::model::snapshot::Snapshot;
use crate::paint::colors;
use crate::pseudocode::Task;

/// The most nodes of a level drawn (past it, the level is cut and the panel says so).
pub const LEVEL_CAP: usize = 4_096;
/// The most marked nodes drawn.
const MARK_CAP: usize = 4_096;

/// A translucent polygon (a splitting plane cut to its node).
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Corners in order around it.
    pub corners: Vec<Vec3>,
    /// Its colour.
    pub color: [f32; 4],
}

/// A screen-facing disc at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dot {
    /// Where.
    pub at: Vec3,
    /// Its radius on screen, in points.
    pub radius: f32,
    /// Its colour.
    pub color: [f32; 4],
}

/// Everything the 3D view draws this frame besides the mesh itself.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Draw3d {
    /// Depth-tested segments: the structure.
    pub lines: Vec<Segment>,
    /// Segments drawn on top: the ray, the normal, the gizmo.
    pub overlay: Vec<Segment>,
    /// Translucent polygons.
    pub polygons: Vec<Polygon>,
    /// Markers, on top.
    pub dots: Vec<Dot>,
    /// Triangles drawn in a colour over the mesh.
    pub highlights: Vec<(u32, [f32; 4])>,
    /// Whether the level was cut at [`LEVEL_CAP`] nodes.
    pub level_cut: bool,
}

/// An egui colour as gamma-space RGBA in `0..=1`, with `alpha` as its opacity.
pub fn rgba(c: Color32, alpha: f32) -> [f32; 4] {
    let [r, g, b, _] = c.to_srgba_unmultiplied();
    [
        f32::from(r) / 255.0,
        f32::from(g) / 255.0,
        f32::from(b) / 255.0,
        alpha,
    ]
}

/// The structure a lane built on the mesh as it is.
type Built3d = Structure<Triangle3>;

impl Draw3d {
    fn node(&mut self, built: &Built3d, id: NodeId, color: [f32; 4], width: f32) {
        if let Some(view) = built.node(id) {
            wire::shape(&view.shape, color, width, &mut self.lines);
        }
    }
}

/// The most triangles of a hovered node's subtree lit.
const HOVER_TRIANGLE_CAP: usize = 200_000;

/// What the pointer is on outside the view that the view lights: a node of this lane (in
/// the tree diagram or on the mesh) and a row of the §2 table.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Lit {
    /// The node hovered.
    pub node: Option<NodeId>,
    /// The bounding volume whose row is hovered.
    pub volume: Option<bvhlab::FitKind>,
}

/// The draw list of lane `index` (1: the comparison) in a view of `rect`, with what is
/// `lit` lit, and in the main lane what Predict's question is `asked` about.
pub fn draw(
    lab: &Lab3d,
    index: usize,
    rect: egui::Rect,
    gizmo_shown: bool,
    lit: Lit,
    asked: &About,
) -> Draw3d {
    let mut d = Draw3d::default();
    // The volumes are the mesh's, not a structure's: drawn while one builds or is none.
    super::volumes::draw_volumes(lab, lit.volume, &mut d);
    super::sat::draw_sat(lab, &mut d);
    super::collision::draw_collision(lab, &mut d);
    let task = lab.half.task;
    let lane = lab.half.lane_at(index);
    let (Some(mesh), Some(built)) = (&lab.mesh, lane.current(lab.revision())) else {
        return d;
    };
    let size = mesh.size();
    let snap = lane.snapshot.as_ref();
    let building = task == Task::Build && snap.is_some();
    if lab.display.structure {
        structure_level(lab, built, snap.filter(|_| building), &mut d);
    }
    if let Some(snap) = snap {
        if building {
            build_state(lab, built, snap, &mut d);
        } else if lab.display.marks {
            query_marks(built, snap, &mut d);
        }
        tested(snap, &mut d);
    }
    if !building {
        query_shapes(lab, lane, task, size, &mut d);
    }
    if index == 0 {
        asked_about(built, asked, &mut d);
    }
    if let Some(node) = lit.node {
        hovered_node(built, node, &mut d);
    }
    if gizmo_shown {
        gizmo(lab, rect, &mut d);
    }
    d
}

/// The nodes of the chosen level, faint; their splitting planes, translucent.
fn structure_level(lab: &Lab3d, built: &Built3d, build: Option<&Snapshot<Vec3>>, d: &mut Draw3d) {
    let (level, cut) = built.level(lab.display.depth, LEVEL_CAP);
    d.level_cut = cut;
    let color = rgba(colors::STRUCTURE, 0.55);
    // Planes fade as the level fills up, so the mesh still shows through a deep level.
    let inner = level.iter().filter(|n| !n.splits.is_empty()).count().max(1);
    let plane = rgba(
        colors::SLAB_Y,
        (0.18 * (4.0 / inner as f32).sqrt()).clamp(0.03, 0.18),
    );
    for node in &level {
        // A build shows only the nodes made so far.
        if let Some(snap) = build
            && !snap.existing.get(node.id.index()).copied().unwrap_or(false)
        {
            continue;
        }
        wire::shape(&node.shape, color, 1.0, &mut d.lines);
        for split in &node.splits {
            let corners = wire::plane_in_box(split, &node.shape.aabb());
            if !corners.is_empty() {
                d.polygons.push(Polygon {
                    corners,
                    color: plane,
                });
            }
        }
    }
}

/// Visited, culled and pruned nodes; the current node; the waiting ones; grid cells.
fn query_marks(built: &Built3d, snap: &Snapshot<Vec3>, d: &mut Draw3d) {
    let mut drawn = 0;
    for (index, mark) in snap.marks.nodes.iter().enumerate() {
        let Some(mark) = mark else { continue };
        if drawn >= MARK_CAP {
            break;
        }
        drawn += 1;
        let (color, width) = match mark {
            NodeMark::Visited => (colors::VISITED, 1.8),
            NodeMark::Culled => (colors::CULLED, 1.4),
            NodeMark::Pruned => (colors::PRUNED, 1.4),
        };
        d.node(built, NodeId(index as u32), rgba(color, 0.9), width);
    }
    for pending in &snap.frontier {
        d.node(built, pending.node, rgba(colors::WAITING, 0.95), 2.0);
    }
    if let Some(current) = snap.current {
        d.node(built, current, rgba(colors::CURRENT, 1.0), 3.0);
    }
}

/// The triangles tested so far (the best in the answer's colour).
fn tested(snap: &Snapshot<Vec3>, d: &mut Draw3d) {
    for &(prim, result) in &snap.marks.tested {
        let color = match result {
            PrimitiveResult::Hit(_) | PrimitiveResult::Overlap => rgba(colors::TESTED, 1.0),
            _ => rgba(colors::TESTED, 0.6),
        };
        d.highlights.push((prim, color));
    }
    for &(prim, _) in &snap.best {
        d.highlights.push((prim, rgba(colors::ANSWER, 1.0)));
    }
}

/// A build: the current node's triangles by the side of the split they go to, and the
/// split plane.
fn build_state(lab: &Lab3d, built: &Built3d, snap: &Snapshot<Vec3>, d: &mut Draw3d) {
    let Some(current) = snap.current else { return };
    d.node(built, current, rgba(colors::CURRENT, 1.0), 3.0);
    let Some(view) = built.node(current) else {
        return;
    };
    let Some(split) = snap.split.filter(|s| s.node == current) else {
        return;
    };
    let plane = bvhlab::SplitPlane {
        normal: split.normal,
        offset: split.offset,
    };
    let corners = wire::plane_in_box(&plane, &view.shape.aabb());
    if !corners.is_empty() {
        d.polygons.push(Polygon {
            corners,
            color: rgba(colors::SLAB_X, 0.35),
        });
    }
    // The triangles below the node, coloured by their centre's side of the plane.
    let mut stack = vec![current];
    let mut count = 0;
    while let Some(id) = stack.pop() {
        if count > 200_000 {
            break;
        }
        let children = built.children(id);
        if children.is_empty() {
            for prim in built.leaf_primitives(id) {
                count += 1;
                if let Some(t) = lab.triangle(prim) {
                    let below = split.normal.dot(t.centroid()) < split.offset;
                    let color = if below {
                        colors::FIRST_SIDE
                    } else {
                        colors::SECOND_SIDE
                    };
                    d.highlights.push((prim, rgba(color, 1.0)));
                }
            }
        } else {
            stack.extend(children);
        }
    }
}

/// What Predict's question waiting is about: its nodes on top of the mesh (as the node
/// hovered is), its triangles in the asked colour. The tree diagram and the question name
/// them.
fn asked_about(built: &Built3d, about: &About, d: &mut Draw3d) {
    let color = rgba(colors::ASKED, 1.0);
    for &node in &about.nodes {
        if let Some(view) = built.node(node) {
            wire::shape(&view.shape, color, 2.5, &mut d.overlay);
        }
    }
    d.highlights.extend(about.prims.iter().map(|&p| (p, color)));
}

/// The node hovered: its volume or cell on top of the mesh (so it shows inside an opaque
/// one), and the triangles below it, over the other highlights.
fn hovered_node(built: &Built3d, node: NodeId, d: &mut Draw3d) {
    let Some(view) = built.node(node) else { return };
    let color = rgba(colors::SELECTED, 1.0);
    wire::shape(&view.shape, color, 2.5, &mut d.overlay);
    let mut stack = vec![node];
    let mut count = 0;
    while let Some(id) = stack.pop() {
        let children = built.children(id);
        if children.is_empty() {
            for prim in built.leaf_primitives(id) {
                if count >= HOVER_TRIANGLE_CAP {
                    return;
                }
                count += 1;
                d.highlights.push((prim, color));
            }
        } else {
            stack.extend(children);
        }
    }
}

/// The ray with its hit and normal; the query point with its closest points or range.
fn query_shapes(lab: &Lab3d, lane: &Lane<Triangle3>, task: Task, size: f32, d: &mut Draw3d) {
    let ray_task = matches!(task, Task::FirstHit | Task::AnyHit | Task::AllHits);
    if ray_task && let Some(ray) = lab.ray {
        let unit = ray.dir().length().max(1e-12);
        let best_t = lane
            .snapshot
            .as_ref()
            .and_then(|s| s.best.first().map(|b| b.1));
        let far = best_t.unwrap_or(size * 4.0 / unit);
        d.overlay.push(Segment {
            a: ray.origin(),
            b: ray.origin() + ray.dir() * far,
            color: rgba(colors::QUERY, 1.0),
            width: 2.5,
        });
        if let (Some(t), Some((prim, _))) = (
            best_t,
            lane.snapshot.as_ref().and_then(|s| s.best.first().copied()),
        ) {
            let hit = ray.origin() + ray.dir() * t;
            d.dots.push(Dot {
                at: hit,
                radius: 6.0,
                color: rgba(colors::ANSWER, 1.0),
            });
            if let Some(tri) = lab.triangle(prim) {
                let n = tri.normal().normalize_or_zero();
                // The normal that faces the ray.
                let n = if n.dot(ray.dir()) > 0.0 { -n } else { n };
                d.overlay.push(Segment {
                    a: hit,
                    b: hit + n * size * 0.08,
                    color: rgba(colors::SELECTED, 1.0),
                    width: 2.5,
                });
            }
        }
    }
    if matches!(task, Task::Nearest | Task::Range)
        && let Some(point) = lab.point
    {
        d.dots.push(Dot {
            at: point,
            radius: 6.0,
            color: rgba(colors::QUERY, 1.0),
        });
        if task == Task::Range {
            for plane in [(Vec3::X, Vec3::Y), (Vec3::Y, Vec3::Z), (Vec3::Z, Vec3::X)] {
                wire::circle(
                    point,
                    lab.half.radius,
                    plane,
                    rgba(colors::QUERY, 0.8),
                    1.5,
                    &mut d.overlay,
                );
            }
        }
        if task == Task::Nearest
            && let Some(snap) = &lane.snapshot
        {
            for &(prim, _) in &snap.best {
                if let Some(tri) = lab.triangle(prim) {
                    let closest = tri.project_point(point);
                    d.overlay.push(Segment {
                        a: point,
                        b: closest,
                        color: rgba(colors::ANSWER, 1.0),
                        width: 2.0,
                    });
                    d.dots.push(Dot {
                        at: closest,
                        radius: 5.0,
                        color: rgba(colors::ANSWER, 1.0),
                    });
                }
            }
        }
    }
}

/// The gizmo's handles: the ray's origin and direction, or the point, with axis arrows to
/// drag along.
fn gizmo(lab: &Lab3d, rect: egui::Rect, d: &mut Draw3d) {
    for (handle, at) in super::input::handles(lab, rect) {
        let color = match handle {
            Handle::Axis(axis, _) => [colors::SLAB_X, colors::VISITED, colors::SLAB_Y][axis],
            Handle::RayDirection => colors::SELECTED,
            _ => Color32::WHITE,
        };
        if let Handle::Axis(_, base) = handle {
            d.overlay.push(Segment {
                a: base,
                b: at,
                color: rgba(color, 1.0),
                width: 2.0,
            });
        }
        d.dots.push(Dot {
            at,
            radius: 5.0,
            color: rgba(color, 1.0),
        });
    }
}
