//! Convex hulls as bounding volumes (lecture §2, "Convex hull"). PLACEHOLDER: being written.

use crate::Vector;

/// The convex hull of a point set. PLACEHOLDER.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexHull<V: Vector> {
    vertices: Vec<V>,
    facets: Vec<V::Facet>,
}

impl<V: Vector> ConvexHull<V> {
    /// PLACEHOLDER.
    pub fn from_points(points: &[V]) -> Self {
        V::convex_hull(points)
    }
}

pub(crate) fn placeholder<V: Vector>(points: &[V]) -> ConvexHull<V> {
    ConvexHull { vertices: points.to_vec(), facets: Vec::new() }
}
