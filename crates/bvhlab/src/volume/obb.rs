//! PLACEHOLDER: oriented boxes.
use crate::Vector;
/// An oriented box. PLACEHOLDER.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb<V: Vector> {
    /// Centre.
    pub center: V,
    /// Orthonormal axes.
    pub axes: V::Axes,
    /// Half side lengths along the axes.
    pub half_extents: V,
}
impl<V: Vector> Obb<V> {
    /// PLACEHOLDER.
    pub fn pca_fit(points: &[V]) -> Self {
        let _ = points;
        Self { center: V::ZERO, axes: V::principal_axes(points), half_extents: V::ZERO }
    }
}
