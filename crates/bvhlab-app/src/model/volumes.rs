//! Lecture §2 as data: the bounding volumes of the selected shapes, the slab test of a ray
//! against their AABB (with the naive formula beside the core's, for "when does this fail?"),
//! the ray-sphere quadratic, and two oriented boxes under the separating-axis test. The fits
//! and the slab test serve both halves: a 2D selection of shapes and a 3D part of a mesh.

use bvhlab::glam::Vec2;
use bvhlab::volume::AxisTest;
use bvhlab::{Aabb, ConvexHull, FitKind, FitReport, Obb, Obb2, PcaFit, Ray, Sphere, Vector};

/// Every bounding volume of a point set, fitted by the core.
#[derive(Clone, Debug)]
pub struct Fits<V: Vector = Vec2> {
    /// The lecture's sphere: centroid and the farthest vertex.
    pub centroid: Sphere<V>,
    /// Ritter's sphere.
    pub ritter: Sphere<V>,
    /// Welzl's minimal sphere.
    pub welzl: Sphere<V>,
    /// The axis-aligned box.
    pub aabb: Aabb<V>,
    /// The PCA box.
    pub obb: Obb<V>,
    /// Where the PCA box's axes came from (mean, covariance, variances).
    pub pca: PcaFit<V>,
    /// The convex hull.
    pub hull: ConvexHull<V>,
    /// Sizes and tightness (hull measure over each volume's measure): areas and perimeters
    /// in 2D, volumes and surface areas in 3D.
    pub report: FitReport,
}

impl<V: Vector> Fits<V> {
    /// The fits of `points`, or `None` when there are none.
    pub fn of(points: &[V]) -> Option<Self> {
        if points.is_empty() {
            return None;
        }
        let (obb, pca) = Obb::pca_fit_detailed(points);
        Some(Self {
            centroid: Sphere::centroid_fit(points),
            ritter: Sphere::ritter_fit(points),
            welzl: Sphere::welzl_fit(points),
            aabb: Aabb::from_points(points),
            obb,
            pca,
            hull: ConvexHull::from_points(points),
            report: FitReport::for_points(points),
        })
    }

    /// The sphere fitted the way `kind` names (`None` for the other kinds).
    pub fn sphere(&self, kind: FitKind) -> Option<&Sphere<V>> {
        match kind {
            FitKind::SphereCentroid => Some(&self.centroid),
            FitKind::SphereRitter => Some(&self.ritter),
            FitKind::SphereWelzl => Some(&self.welzl),
            _ => None,
        }
    }

    /// The box around the volumes `shown` (the spheres and the OBB reach beyond the shape's
    /// own box): what "Fit view" frames besides the scene.
    pub fn bounds(&self, shown: &VolumeToggles) -> Aabb<V> {
        let mut points = vec![self.aabb.min, self.aabb.max];
        for (on, sphere) in [
            (shown.centroid, &self.centroid),
            (shown.ritter, &self.ritter),
            (shown.welzl, &self.welzl),
        ] {
            if on {
                points.push(sphere.center - V::splat(sphere.radius));
                points.push(sphere.center + V::splat(sphere.radius));
            }
        }
        if shown.obb {
            points.extend(self.obb.corners());
        }
        points.retain(|p| p.is_finite());
        Aabb::from_points(&points)
    }
}

/// Which volumes are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(clippy::struct_excessive_bools)] // one switch per volume, as the panel shows them
pub struct VolumeToggles {
    /// The centroid sphere.
    pub centroid: bool,
    /// Ritter's sphere.
    pub ritter: bool,
    /// Welzl's sphere.
    pub welzl: bool,
    /// The AABB.
    pub aabb: bool,
    /// The OBB, with its axes.
    pub obb: bool,
    /// The convex hull.
    pub hull: bool,
}

impl VolumeToggles {
    /// Whether the volume `kind` is switched on.
    pub fn has(&self, kind: FitKind) -> bool {
        match kind {
            FitKind::SphereCentroid => self.centroid,
            FitKind::SphereRitter => self.ritter,
            FitKind::SphereWelzl => self.welzl,
            FitKind::Aabb => self.aabb,
            FitKind::Obb => self.obb,
            FitKind::ConvexHull => self.hull,
        }
    }
}

impl Default for VolumeToggles {
    fn default() -> Self {
        Self {
            centroid: true,
            // On: the lecture's three sphere fits are seen side by side.
            ritter: true,
            welzl: true,
            aabb: true,
            obb: true,
            hull: true,
        }
    }
}

/// One axis of the slab test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlabAxis {
    /// The slab's lower and upper planes (`x_min`, `x_max`).
    pub lo: f32,
    /// See `lo`.
    pub hi: f32,
    /// The ray origin's coordinate (`x_e`).
    pub origin: f32,
    /// The direction's coordinate (`x_d`).
    pub dir: f32,
    /// The core's entry and exit along this axis (after the sign swap; `±inf` when parallel).
    pub t_min: f32,
    /// See `t_min`.
    pub t_max: f32,
    /// The slide's formula evaluated naively in IEEE floats: `(x_min - x_e) / x_d` and
    /// `(x_max - x_e) / x_d`, swapped when `x_d < 0`. NaN when `x_d = 0` and the origin lies on
    /// a slab plane.
    pub naive: (f32, f32),
}

impl SlabAxis {
    /// Whether the direction is negative, so the slab ends swap.
    pub fn swapped(&self) -> bool {
        self.dir < 0.0
    }

    /// Whether the ray runs parallel to this slab (`x_d = 0`).
    pub fn parallel(&self) -> bool {
        self.dir == 0.0
    }

    /// Whether the naive formula produced NaN (the "when does this fail?" case).
    pub fn naive_fails(&self) -> bool {
        self.naive.0.is_nan() || self.naive.1.is_nan()
    }
}

/// The slab test of a ray against a box, axis by axis.
#[derive(Clone, Debug, PartialEq)]
pub struct SlabExplain {
    /// x, then y (then z in 3D).
    pub axes: Vec<SlabAxis>,
    /// `max(t_xmin, t_ymin)`, clamped below by 0 (the ray starts at `t = 0`).
    pub t_enter: f32,
    /// `min(t_xmax, t_ymax)`.
    pub t_exit: f32,
}

impl SlabExplain {
    /// The slab test of `ray` against `aabb`, from the core's [`Aabb::slab_test`].
    ///
    /// [`Aabb::slab_test`]: bvhlab::Aabb::slab_test
    pub fn new<V: Vector>(aabb: &Aabb<V>, ray: &Ray<V>) -> Self {
        let slab = aabb.slab_test(ray);
        let axes = (0..V::DIM).map(|i| {
            let (lo, hi) = (aabb.min.coord(i), aabb.max.coord(i));
            let (e, d) = (ray.origin().coord(i), ray.dir().coord(i));
            let (a, b) = ((lo - e) / d, (hi - e) / d);
            SlabAxis {
                lo,
                hi,
                origin: e,
                dir: d,
                t_min: slab.t_near.coord(i),
                t_max: slab.t_far.coord(i),
                naive: if d >= 0.0 { (a, b) } else { (b, a) },
            }
        });
        Self {
            axes: axes.collect(),
            t_enter: slab.t_enter(),
            t_exit: slab.t_exit(),
        }
    }

    /// Whether the ray meets the box (the slide's test, negated: it misses when
    /// `max(t_min) > min(t_max)`).
    pub fn hits(&self) -> bool {
        self.t_enter <= self.t_exit
    }

    /// The naive test's verdict, `None` when it compared a NaN (every comparison with NaN is
    /// false, so the answer depends on how the code is written).
    pub fn naive_hits(&self) -> Option<bool> {
        if self.axes.iter().any(SlabAxis::naive_fails) {
            return None;
        }
        let enter = self.axes.iter().fold(0.0_f32, |t, a| t.max(a.naive.0));
        let exit = self
            .axes
            .iter()
            .fold(f32::INFINITY, |t, a| t.min(a.naive.1));
        Some(enter <= exit)
    }
}

/// One box the student drags in the separating-axis demo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxPose {
    /// Centre.
    pub center: Vec2,
    /// Half extents along the box's own axes.
    pub half: Vec2,
    /// Rotation in radians.
    pub angle: f32,
}

impl BoxPose {
    /// The oriented box.
    pub fn obb(&self) -> Obb2 {
        let u = Vec2::from_angle(self.angle);
        Obb2 {
            center: self.center,
            axes: [u, u.perp()],
            half_extents: self.half,
        }
    }

    /// Where the rotation handle sits (the end of the first axis, a bit beyond the box).
    pub fn handle(&self) -> Vec2 {
        self.center + Vec2::from_angle(self.angle) * (self.half.x + 0.8)
    }
}

/// The two boxes of the separating-axis demo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObbPair {
    /// The first box.
    pub a: BoxPose,
    /// The second box.
    pub b: BoxPose,
}

impl ObbPair {
    /// A pair placed around `center`, `size` apart.
    pub fn around(center: Vec2, size: f32) -> Self {
        Self {
            a: BoxPose {
                center: center - Vec2::new(size * 0.6, 0.0),
                half: Vec2::new(size * 0.5, size * 0.2),
                angle: 0.4,
            },
            b: BoxPose {
                center: center + Vec2::new(size * 0.6, size * 0.1),
                half: Vec2::new(size * 0.35, size * 0.25),
                angle: -0.3,
            },
        }
    }

    /// The separating-axis test, axis by axis (4 axes in 2D), from the core.
    pub fn tests(&self) -> Vec<AxisTest<Vec2>> {
        self.a.obb().sat_tests(&self.b.obb())
    }
}

#[cfg(test)]
mod tests {
    use bvhlab::{Aabb2, Ray2};

    use super::*;

    #[test]
    fn naive_slab_fails_where_the_lecture_says_and_the_core_does_not() {
        let aabb = Aabb2::new(Vec2::new(0.0, 0.0), Vec2::new(4.0, 2.0));
        // Parallel to x, origin exactly on the slab line y = y_min.
        let ray = Ray2::new(Vec2::new(-3.0, 0.0), Vec2::X).expect("ray");
        let explain = SlabExplain::new(&aabb, &ray);
        assert!(explain.axes[1].parallel());
        assert!(explain.axes[1].naive_fails(), "0 / 0 is NaN");
        assert_eq!(explain.naive_hits(), None);
        assert!(
            explain.hits(),
            "the core: a ray along the box's edge touches it"
        );
        // Parallel, not on a slab plane: 1/0 = inf keeps even the naive test right.
        let ray = Ray2::new(Vec2::new(-3.0, 1.0), Vec2::X).expect("ray");
        let explain = SlabExplain::new(&aabb, &ray);
        assert_eq!(explain.naive_hits(), Some(true));
        assert!(explain.hits());
        // Negative direction: the ends swap.
        let ray = Ray2::new(Vec2::new(10.0, 1.0), Vec2::new(-1.0, 0.1)).expect("ray");
        let explain = SlabExplain::new(&aabb, &ray);
        assert!(explain.axes[0].swapped());
        assert!(explain.axes[0].t_min < explain.axes[0].t_max);
        assert_eq!(explain.naive_hits(), Some(explain.hits()));
    }

    #[test]
    fn separating_axis_found_when_apart() {
        let mut pair = ObbPair::around(Vec2::ZERO, 4.0);
        pair.b.center = Vec2::new(20.0, 0.0);
        assert!(pair.tests().iter().any(AxisTest::separates));
        pair.b.center = pair.a.center;
        assert!(!pair.tests().iter().any(AxisTest::separates));
        assert_eq!(pair.tests().len(), 4);
    }

    #[test]
    fn fits_of_a_shape() {
        let pts = [
            Vec2::ZERO,
            Vec2::new(4.0, 0.0),
            Vec2::new(4.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        let fits = Fits::of(&pts).expect("non-empty");
        assert!(fits.welzl.radius <= fits.centroid.radius + 1e-5);
        assert!(Fits::<Vec2>::of(&[]).is_none());
    }
}
