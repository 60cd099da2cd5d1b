//! What the student draws: segments, polylines, polygons and point clouds, and the
//! primitives (segments; a point is a segment of length zero) the core builds structures on.

use std::sync::atomic::{AtomicU64, Ordering};

use bvhlab::Segment2;
use bvhlab::glam::Vec2;

/// The kinds of shape the lab draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShapeKind {
    /// One segment between two points.
    Segment,
    /// An open chain of segments.
    Polyline,
    /// A closed chain: the last point joins the first.
    Polygon,
    /// Separate points.
    Points,
}

impl ShapeKind {
    /// A name for labels.
    pub fn label(self) -> &'static str {
        match self {
            Self::Segment => "segment",
            Self::Polyline => "polyline",
            Self::Polygon => "polygon",
            Self::Points => "point cloud",
        }
    }
}

/// One shape of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// What the points make.
    pub kind: ShapeKind,
    /// Its points, in order.
    pub points: Vec<Vec2>,
}

impl Shape {
    /// A shape, or why it cannot be one (a NaN or infinite coordinate, too few points).
    ///
    /// # Errors
    /// A message naming the bad point, or saying how many points the kind needs.
    pub fn new(kind: ShapeKind, points: Vec<Vec2>) -> Result<Self, String> {
        if let Some((i, p)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
            return Err(format!(
                "point {i} of the {} is not finite ({p}); nothing was added",
                kind.label()
            ));
        }
        let needed = match kind {
            ShapeKind::Segment | ShapeKind::Polyline => 2,
            ShapeKind::Polygon => 3,
            ShapeKind::Points => 1,
        };
        if points.len() < needed {
            return Err(format!(
                "a {} needs at least {needed} points, it got {}",
                kind.label(),
                points.len()
            ));
        }
        Ok(Self { kind, points })
    }

    /// The shape's primitives, in order.
    pub fn primitives(&self) -> impl Iterator<Item = Segment2> + '_ {
        let p = &self.points;
        let (edges, closing) = match self.kind {
            ShapeKind::Points => (0, false),
            ShapeKind::Segment | ShapeKind::Polyline => (p.len().saturating_sub(1), false),
            ShapeKind::Polygon => (p.len().saturating_sub(1), p.len() > 2),
        };
        let points = (self.kind == ShapeKind::Points)
            .then(|| p.iter().map(|&q| Segment2::new(q, q)))
            .into_iter()
            .flatten();
        let chain = (0..edges).map(|i| Segment2::new(p[i], p[i + 1]));
        let close = closing.then(|| Segment2::new(p[p.len() - 1], p[0]));
        points.chain(chain).chain(close)
    }

    /// The distance from `q` to the shape (its outline, or its nearest point).
    pub fn distance(&self, q: Vec2) -> f32 {
        self.primitives()
            .map(|s| s.project_point(q).distance(q))
            .fold(f32::INFINITY, f32::min)
    }
}

/// The scene: shapes in drawing order. Every change gives it a new [`Scene::revision`], so that
/// structures built on it know when to rebuild.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    shapes: Vec<Shape>,
    revision: u64,
}

/// A revision no scene has had: revisions come from one counter, so that a structure or a
/// cache keyed by the revision of one scene is never taken for another scene's (both the
/// default scene and a freshly loaded preset would otherwise be revision 0).
fn next_revision() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

/// The scene's primitives, and which shape each came from.
#[derive(Clone, Debug, Default)]
pub struct Primitives {
    /// The segments, shape by shape.
    pub segments: Vec<Segment2>,
    /// `owner[i]` is the index of the shape that primitive `i` belongs to.
    pub owner: Vec<usize>,
}

impl Scene {
    /// A scene of these shapes.
    pub fn from_shapes(shapes: Vec<Shape>) -> Self {
        Self {
            shapes,
            revision: next_revision(),
        }
    }

    /// The shapes.
    pub fn shapes(&self) -> &[Shape] {
        &self.shapes
    }

    /// Identifies this state of the scene: equal revisions mean an equal scene. Revisions are
    /// unique across scenes (a new preset never reuses the one the structure was built on).
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Adds a shape; returns its index.
    pub fn add(&mut self, shape: Shape) -> usize {
        self.shapes.push(shape);
        self.revision = next_revision();
        self.shapes.len() - 1
    }

    /// Adds a point to shape `index` (a point cloud, polyline or polygon being drawn).
    pub fn push_point(&mut self, index: usize, p: Vec2) {
        if let Some(shape) = self.shapes.get_mut(index)
            && p.is_finite()
        {
            shape.points.push(p);
            self.revision = next_revision();
        }
    }

    /// Removes the shapes whose indices are listed.
    pub fn remove(&mut self, indices: &[usize]) {
        let mut i = 0;
        self.shapes.retain(|_| {
            i += 1;
            !indices.contains(&(i - 1))
        });
        self.revision = next_revision();
    }

    /// Removes every shape.
    pub fn clear(&mut self) {
        self.shapes.clear();
        self.revision = next_revision();
    }

    /// Moves shape `index` by `delta` (ignored when the move would leave finite numbers).
    pub fn translate(&mut self, index: usize, delta: Vec2) {
        if let Some(shape) = self.shapes.get_mut(index)
            && shape.points.iter().all(|&p| (p + delta).is_finite())
        {
            for p in &mut shape.points {
                *p += delta;
            }
            self.revision = next_revision();
        }
    }

    /// The shape nearest to `q` within `tolerance`, if any.
    pub fn pick(&self, q: Vec2, tolerance: f32) -> Option<usize> {
        self.shapes
            .iter()
            .enumerate()
            .map(|(i, s)| (i, s.distance(q)))
            .filter(|&(_, d)| d <= tolerance)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
    }

    /// The scene's primitives.
    pub fn primitives(&self) -> Primitives {
        let mut out = Primitives::default();
        for (i, shape) in self.shapes.iter().enumerate() {
            for s in shape.primitives() {
                out.segments.push(s);
                out.owner.push(i);
            }
        }
        out
    }

    /// The vertices of the listed shapes (all shapes when `indices` is empty).
    pub fn vertices(&self, indices: &[usize]) -> Vec<Vec2> {
        self.shapes
            .iter()
            .enumerate()
            .filter(|(i, _)| indices.is_empty() || indices.contains(i))
            .flat_map(|(_, s)| s.points.iter().copied())
            .collect()
    }

    /// The box around every point, or `None` for an empty scene.
    pub fn bounds(&self) -> Option<(Vec2, Vec2)> {
        let points = self.vertices(&[]);
        let first = *points.first()?;
        Some(
            points
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_become_segments() {
        let square = vec![
            Vec2::ZERO,
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        let polygon = Shape::new(ShapeKind::Polygon, square.clone()).expect("valid");
        assert_eq!(polygon.primitives().count(), 4);
        let polyline = Shape::new(ShapeKind::Polyline, square.clone()).expect("valid");
        assert_eq!(polyline.primitives().count(), 3);
        let cloud = Shape::new(ShapeKind::Points, square).expect("valid");
        assert!(cloud.primitives().all(|s| s.a == s.b));
        assert_eq!(cloud.primitives().count(), 4);
    }

    #[test]
    fn bad_shapes_are_refused_with_a_reason() {
        let err = Shape::new(
            ShapeKind::Segment,
            vec![Vec2::ZERO, Vec2::new(f32::NAN, 0.0)],
        )
        .expect_err("NaN");
        assert!(err.contains("point 1"), "{err}");
        let err = Shape::new(ShapeKind::Polygon, vec![Vec2::ZERO, Vec2::X]).expect_err("short");
        assert!(err.contains("at least 3"), "{err}");
    }

    #[test]
    fn new_scenes_never_share_a_revision() {
        let shape = |x: f32| Shape::new(ShapeKind::Points, vec![Vec2::splat(x)]).expect("ok");
        let a = Scene::from_shapes(vec![shape(0.0)]);
        let b = Scene::from_shapes(vec![shape(1.0)]);
        assert_ne!(a.revision(), b.revision());
    }

    #[test]
    fn edits_bump_the_revision_and_keep_owners() {
        let mut scene = Scene::default();
        let a = scene.add(Shape::new(ShapeKind::Segment, vec![Vec2::ZERO, Vec2::X]).expect("ok"));
        let r = scene.revision();
        scene.translate(a, Vec2::Y);
        assert!(scene.revision() > r);
        assert_eq!(scene.shapes()[0].points[0], Vec2::Y);
        scene.add(Shape::new(ShapeKind::Points, vec![Vec2::ONE, Vec2::ZERO]).expect("ok"));
        let prims = scene.primitives();
        assert_eq!(prims.owner, vec![0, 1, 1]);
        assert_eq!(scene.pick(Vec2::new(0.5, 1.1), 0.2), Some(0));
        scene.remove(&[0]);
        assert_eq!(scene.shapes().len(), 1);
    }
}
