//! Three ways to fit a sphere to points, from loosest to tightest: the lecture's centroid fit,
//! Ritter's two-pass approximation, and Welzl's exact minimal enclosing sphere.
//!
//! Every fit ends the same way: the radius is recomputed as `max |p - center|` with the very
//! formula [`contains`](super::BoundingVolume::contains) uses (in `f64`, rounded up to `f32`),
//! so rounding can never leave a fitted point outside its sphere.

use glam::DVec3;

use super::sphere::round_up;
use super::{Sphere, checked_points, finite_points};
use crate::Vector;
use crate::error::GeometryError;
use crate::math::linear_solve::solve;

impl<V: Vector> Sphere<V> {
    /// The lecture's sphere: centre `c = (1/n) Σ v_i`, radius `r = max_i |v_i - c|`.
    ///
    /// Simple and stable, but not the smallest sphere: a cluster of points on one side pulls
    /// the centroid away from the middle. Non-finite points are skipped; no points give
    /// [`Sphere::EMPTY`].
    pub fn centroid_fit(points: &[V]) -> Self {
        let points = finite_points(points);
        if points.is_empty() {
            return Self::EMPTY;
        }
        let sum: DVec3 = points.iter().map(|p| p.to_dvec3()).sum();
        let center = V::from_dvec3(sum / points.len() as f64);
        enclosing(center, &points)
    }

    /// Ritter's approximate bounding sphere (J. Ritter, "An Efficient Bounding Sphere",
    /// Graphics Gems, 1990): start from the sphere on an approximately farthest pair (the
    /// point farthest from an arbitrary point, then the point farthest from that one), then
    /// grow it just enough to take in each point left outside, in one pass.
    ///
    /// Linear time; typically 5-20% larger than the minimum. Non-finite points are skipped.
    pub fn ritter_fit(points: &[V]) -> Self {
        let points = finite_points(points);
        let Some(&first) = points.first() else {
            return Self::EMPTY;
        };
        let farthest_from = |q: V| {
            points
                .iter()
                .copied()
                .max_by(|a, b| {
                    (*a - q)
                        .length_squared()
                        .total_cmp(&(*b - q).length_squared())
                })
                .unwrap_or(q)
        };
        let y = farthest_from(first);
        let z = farthest_from(y);
        let mut sphere = Self::new((y + z) * 0.5, (z - y).length() * 0.5);
        for &p in points.iter() {
            let dist = (p - sphere.center).length();
            if dist > sphere.radius {
                // The new sphere touches p and the far side of the old one.
                let radius = 0.5 * (sphere.radius + dist);
                let center =
                    sphere.center + (p - sphere.center) * ((radius - sphere.radius) / dist);
                sphere = Self::new(center, radius);
            }
        }
        enclosing(sphere.center, &points)
    }

    /// The smallest enclosing sphere, exactly (up to floating-point rounding): Welzl's
    /// randomized algorithm (E. Welzl, "Smallest enclosing disks (balls and ellipsoids)",
    /// 1991), in expected linear time.
    ///
    /// Written iteratively over the points as in Gärtner's "Fast and Robust Smallest
    /// Enclosing Balls" (ESA 1999), so the recursion depth is bounded by the number of
    /// support points (`DIM + 1`), not by the number of points. Points are visited in a fixed
    /// pseudo-random order, so the result is deterministic. Arithmetic is in `f64`.
    /// Non-finite points are skipped; no points give [`Sphere::EMPTY`].
    pub fn welzl_fit(points: &[V]) -> Self {
        let points = finite_points(points);
        if points.is_empty() {
            return Self::EMPTY;
        }
        let mut shuffled: Vec<DVec3> = points.iter().map(|p| p.to_dvec3()).collect();
        shuffle(&mut shuffled);
        let scale = shuffled
            .iter()
            .fold(0.0f64, |m, p| m.max(p.abs().max_element()));
        let mut support = Vec::with_capacity(V::DIM + 1);
        let ball = welzl(&shuffled, &mut support, V::DIM, scale);
        enclosing(V::from_dvec3(ball.center), &points)
    }

    /// [`Sphere::centroid_fit`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    pub fn try_centroid_fit(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::centroid_fit)
    }

    /// [`Sphere::ritter_fit`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    pub fn try_ritter_fit(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::ritter_fit)
    }

    /// [`Sphere::welzl_fit`], refusing empty or non-finite input.
    ///
    /// # Errors
    /// [`GeometryError::Empty`] or [`GeometryError::NonFinite`] (naming the point).
    pub fn try_welzl_fit(points: &[V]) -> Result<Self, GeometryError> {
        checked_points(points).map(Self::welzl_fit)
    }
}

/// The sphere around `center` whose radius is the largest distance to a point, measured as
/// `contains` measures it.
fn enclosing<V: Vector>(center: V, points: &[V]) -> Sphere<V> {
    let probe = Sphere::new(center, 0.0);
    let radius = points
        .iter()
        .map(|&p| probe.center_distance(p))
        .fold(0.0f64, f64::max);
    Sphere::new(center, round_up(radius))
}

/// A ball in double precision, during Welzl's algorithm.
#[derive(Clone, Copy, Debug)]
struct Ball {
    center: DVec3,
    radius: f64,
}

impl Ball {
    /// Containment with a relative tolerance: a point that rounding puts a hair outside a
    /// ball through it must not trigger a new (degenerate) support set.
    fn contains(&self, p: DVec3, scale: f64) -> bool {
        (p - self.center).length() <= self.radius + 1e-12 * scale.max(self.radius)
    }
}

/// The smallest ball of `points` with every point of `support` on its boundary.
fn welzl(points: &[DVec3], support: &mut Vec<DVec3>, dim: usize, scale: f64) -> Ball {
    let mut ball = ball_through(support);
    if support.len() == dim + 1 {
        return ball;
    }
    for (i, &p) in points.iter().enumerate() {
        if !ball.contains(p, scale) {
            support.push(p);
            ball = welzl(&points[..i], support, dim, scale);
            support.pop();
        }
    }
    ball
}

/// The smallest ball with all of `support` (at most 4 points) on its boundary: its centre is
/// the circumcentre within their affine hull, `c = p0 + Σ λ_k (p_k - p0)`, where
/// `2 (p_j - p0)·(c - p0) = |p_j - p0|²` for each j.
fn ball_through(support: &[DVec3]) -> Ball {
    let Some((&p0, rest)) = support.split_first() else {
        return Ball {
            center: DVec3::ZERO,
            radius: -1.0,
        };
    };
    let q: Vec<DVec3> = rest.iter().map(|&p| p - p0).collect();
    let n = q.len();
    let mut gram = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for j in 0..n {
        for k in 0..n {
            gram[j][k] = 2.0 * q[j].dot(q[k]);
        }
        rhs[j] = q[j].length_squared();
    }
    let center = match solve(gram, rhs, n) {
        Some(lambda) => p0 + q.iter().zip(lambda).map(|(&qk, l)| qk * l).sum::<DVec3>(),
        // Affinely dependent support (only possible through rounding): the ball on the
        // farthest pair is the best that can be said, and the final radius covers the rest.
        None => farthest_pair_midpoint(support),
    };
    let radius = support
        .iter()
        .map(|&p| (p - center).length())
        .fold(0.0, f64::max);
    Ball { center, radius }
}

fn farthest_pair_midpoint(points: &[DVec3]) -> DVec3 {
    let mut best = (0.0, points[0], points[0]);
    for (i, &a) in points.iter().enumerate() {
        for &b in &points[i + 1..] {
            let d = a.distance_squared(b);
            if d > best.0 {
                best = (d, a, b);
            }
        }
    }
    (best.1 + best.2) * 0.5
}

/// A deterministic Fisher-Yates shuffle driven by `SplitMix64` (Steele, Lea and Flood, 2014):
/// Welzl's expected linear time needs a random order, and repeatable results need a fixed one.
fn shuffle<T>(items: &mut [T]) {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15 ^ items.len() as u64;
    let mut next = || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    for i in (1..items.len()).rev() {
        let j = (next() % (i as u64 + 1)) as usize;
        items.swap(i, j);
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};

    use super::*;
    use crate::volume::BoundingVolume;

    #[test]
    fn welzl_on_a_right_triangle_is_the_hypotenuse_circle() {
        let s = Sphere::welzl_fit(&[Vec2::ZERO, Vec2::new(4.0, 0.0), Vec2::new(0.0, 2.0)]);
        assert!((s.center - Vec2::new(2.0, 1.0)).length() < 1e-6);
        assert!((s.radius - 5f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn welzl_on_an_obtuse_triangle_is_the_longest_side_circle() {
        let s = Sphere::welzl_fit(&[Vec2::ZERO, Vec2::new(4.0, 0.0), Vec2::new(2.0, 0.5)]);
        assert!((s.center - Vec2::new(2.0, 0.0)).length() < 1e-6);
        assert!((s.radius - 2.0).abs() < 1e-6);
    }

    #[test]
    fn welzl_on_a_regular_tetrahedron_is_its_circumsphere() {
        let pts = [
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
        ];
        let s = Sphere::welzl_fit(&pts);
        assert!(s.center.length() < 1e-6);
        assert!((s.radius - 3f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn fits_of_nothing_are_empty_and_of_one_point_are_that_point() {
        assert!(Sphere::<Vec3>::welzl_fit(&[]).is_empty());
        assert!(Sphere::<Vec2>::ritter_fit(&[Vec2::NAN]).is_empty());
        let p = Vec3::new(1.0, 2.0, 3.0);
        for s in [
            Sphere::centroid_fit(&[p]),
            Sphere::ritter_fit(&[p]),
            Sphere::welzl_fit(&[p]),
        ] {
            assert_eq!((s.center, s.radius), (p, 0.0));
        }
    }

    #[test]
    fn shuffle_is_a_permutation() {
        let mut v: Vec<u32> = (0..100).collect();
        shuffle(&mut v);
        assert_ne!(v, (0..100).collect::<Vec<_>>());
        v.sort_unstable();
        assert_eq!(v, (0..100).collect::<Vec<_>>());
    }
}
