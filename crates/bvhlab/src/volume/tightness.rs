//! How tightly each bounding volume fits a point set (lecture §2: "should fit tightly").
//!
//! The convex hull is the tightest convex volume, so each volume's tightness is the hull's
//! area (2D) or volume (3D) divided by its own: 1 means as tight as the hull, 0.5 means half
//! of the volume is empty space that rays and distance queries will waste time on.

use super::{Aabb, BoundingVolume, ConvexHull, Obb, Sphere};
use crate::Vector;

/// Which fit a [`FitMeasure`] describes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FitKind {
    /// [`Sphere::centroid_fit`], the lecture's sphere.
    SphereCentroid,
    /// [`Sphere::ritter_fit`].
    SphereRitter,
    /// [`Sphere::welzl_fit`], the minimal sphere.
    SphereWelzl,
    /// [`Aabb::from_points`].
    Aabb,
    /// [`Obb::pca_fit`].
    Obb,
    /// [`ConvexHull::from_points`].
    ConvexHull,
}

impl FitKind {
    /// Every kind, loosest family first, in the order the lecture introduces them.
    pub const ALL: [FitKind; 6] = [
        FitKind::SphereCentroid,
        FitKind::SphereRitter,
        FitKind::SphereWelzl,
        FitKind::Aabb,
        FitKind::Obb,
        FitKind::ConvexHull,
    ];

    /// A short label for tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            FitKind::SphereCentroid => "sphere (centroid)",
            FitKind::SphereRitter => "sphere (Ritter)",
            FitKind::SphereWelzl => "sphere (Welzl, minimal)",
            FitKind::Aabb => "AABB",
            FitKind::Obb => "OBB (PCA)",
            FitKind::ConvexHull => "convex hull",
        }
    }
}

/// The size of one fitted volume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitMeasure {
    /// Which fit.
    pub kind: FitKind,
    /// Area (2D) or volume (3D).
    pub measure: f32,
    /// Perimeter (2D) or surface area (3D).
    pub boundary_measure: f32,
    /// Hull measure / this measure, in `(0, 1]`. For a degenerate point set whose hull has
    /// no area (volume), the ratio of boundary measures is used instead; `None` when that is
    /// zero too (a single point, or no points).
    pub tightness: Option<f32>,
}

/// Every fit of one point set, side by side.
#[derive(Clone, Debug, PartialEq)]
pub struct FitReport {
    /// One entry per [`FitKind::ALL`], in that order.
    pub fits: Vec<FitMeasure>,
}

impl FitReport {
    /// Fits every volume to `points` and measures it (non-finite points are skipped, as the
    /// lenient fits do).
    pub fn for_points<V: Vector>(points: &[V]) -> Self {
        let hull = ConvexHull::from_points(points);
        let (hull_m, hull_b) = sizes(&hull);
        let fits = FitKind::ALL
            .iter()
            .map(|&kind| {
                let (measure, boundary_measure) = match kind {
                    FitKind::SphereCentroid => sizes(&Sphere::centroid_fit(points)),
                    FitKind::SphereRitter => sizes(&Sphere::ritter_fit(points)),
                    FitKind::SphereWelzl => sizes(&Sphere::welzl_fit(points)),
                    FitKind::Aabb => sizes(&Aabb::from_points(points)),
                    FitKind::Obb => sizes(&Obb::pca_fit(points)),
                    FitKind::ConvexHull => (hull_m, hull_b),
                };
                let tightness = if hull_m > 0.0 && measure > 0.0 {
                    Some(hull_m / measure)
                } else if hull_b > 0.0 && boundary_measure > 0.0 {
                    Some(hull_b / boundary_measure)
                } else {
                    None
                };
                FitMeasure {
                    kind,
                    measure,
                    boundary_measure,
                    tightness,
                }
            })
            .collect();
        Self { fits }
    }

    /// The entry for one kind.
    pub fn get(&self, kind: FitKind) -> Option<&FitMeasure> {
        self.fits.iter().find(|f| f.kind == kind)
    }
}

fn sizes<B: BoundingVolume>(volume: &B) -> (f32, f32) {
    (volume.measure(), volume.boundary_measure())
}
