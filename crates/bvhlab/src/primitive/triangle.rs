//! Triangles in 3D: the watertight ray-triangle test and the closest point on a triangle.

use glam::{DVec3, Vec3};

use super::Primitive;
use crate::Ray3;
use crate::volume::Aabb;

/// A triangle with corners `a`, `b`, `c`; meshes are slices of these.
///
/// Seen from the side its [`normal`](Primitive::normal) points to, the corners run
/// counter-clockwise. Ray tests hit both sides. A degenerate triangle (zero area) is never hit
/// by a ray, but its closest point is still well defined (on one of its edges).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct Triangle3 {
    /// First corner.
    pub a: Vec3,
    /// Second corner.
    pub b: Vec3,
    /// Third corner.
    pub c: Vec3,
}

/// The coordinates of a vertex relative to the ray origin, in the ray's sheared frame.
#[derive(Clone, Copy)]
struct Sheared {
    x: f32,
    y: f32,
    z: f32,
}

/// What the watertight test computes from the ray's direction alone (Woop, Benthin and
/// Wald 2013, §3): the axes that become x, y and z, and the shear that turns the direction
/// into +z. [`Ray`](crate::Ray) computes it once, when it is made.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct RayShear {
    /// The direction's dominant axis (the one that becomes z), and the two others, in the
    /// order that keeps the winding.
    kx: u8,
    ky: u8,
    kz: u8,
    /// `d[kx] / d[kz]`, `d[ky] / d[kz]`, `1 / d[kz]`.
    sx: f32,
    sy: f32,
    sz: f32,
}

impl RayShear {
    /// The axes that become x, y and z, and the shears of x and y: what a test of several
    /// triangles at once needs to move their corners exactly as [`apply`](Self::apply)
    /// does (the wide tree's four-triangle blocks).
    #[inline]
    pub(crate) fn axes_and_shear(&self) -> ([usize; 3], [f32; 2]) {
        (
            [
                usize::from(self.kx),
                usize::from(self.ky),
                usize::from(self.kz),
            ],
            [self.sx, self.sy],
        )
    }

    /// A point relative to the ray's origin, in the ray's frame: permuted and sheared so
    /// that the ray runs along +z. A function, not a closure: WebAssembly builds left the
    /// closure out of line, a call per corner.
    #[inline]
    fn apply(&self, p: Vec3) -> Sheared {
        let (x, y, z) = (
            Self::pick(p, self.kx),
            Self::pick(p, self.ky),
            Self::pick(p, self.kz),
        );
        Sheared {
            x: x - self.sx * z,
            y: y - self.sy * z,
            z: self.sz * z,
        }
    }

    /// Coordinate `k` (0, 1 or 2) of `p`.
    #[inline]
    fn pick(p: Vec3, k: u8) -> f32 {
        match k {
            0 => p.x,
            1 => p.y,
            _ => p.z,
        }
    }

    /// The setup for direction `d`. Mirrored in WGSL at the end of `prepare_ray` in the app's
    /// heat map shader (`trace.wgsl`): a change here must be made there too.
    pub(crate) fn of(d: Vec3) -> Self {
        // kz: the dominant axis of the direction; kx, ky follow it cyclically, swapped when
        // d[kz] < 0 to keep the winding (and so the sign convention) unchanged.
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self {
            kx: kx as u8,
            ky: ky as u8,
            kz: kz as u8,
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            sz: 1.0 / d[kz],
        }
    }
}

impl Triangle3 {
    /// The triangle with corners `a`, `b`, `c`.
    pub const fn new(a: Vec3, b: Vec3, c: Vec3) -> Self {
        Self { a, b, c }
    }

    /// The `t >= 0` at which the ray crosses the triangle, if it does.
    ///
    /// Watertight: Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection", JCGT 2(1),
    /// 2013. The ray is turned into the +z axis by a permutation and a shear; each edge test is
    /// then a 2D cross product of two transformed corners. A corner's transformed coordinates
    /// depend only on that corner and the ray, so triangles sharing an edge compute the same
    /// edge value with opposite signs, and a ray through a shared edge or vertex of a closed
    /// mesh hits at least one of the triangles there. The edge tests and `t` are evaluated in
    /// `f64` (the paper's fallback for exact zeros, made the rule), which also keeps them exact
    /// in sign at any `f32` scale. Both sides are hit; a ray in the triangle's plane is not.
    ///
    /// Mirrored in WGSL by `ray_triangle` (with `shear`, `edge` and `edge_sign`, and the
    /// `f64` arithmetic of `exact.wgsl` beside it) in the app's heat map shader
    /// (`crates/bvhlab-app/src/render3d/heatmap/trace.wgsl`), which must give the same hits and `t`
    /// bit for bit: a change here (or in `RayShear::of`) must be made there too.
    #[inline]
    pub fn ray_hit(&self, ray: &Ray3) -> Option<f32> {
        let (corners, weights, det) = self.sheared_weights(ray)?;
        let t_scaled = weights[0] * f64::from(corners[0].z)
            + weights[1] * f64::from(corners[1].z)
            + weights[2] * f64::from(corners[2].z);
        // t = t_scaled / det must be >= 0: same sign, or zero.
        if (det > 0.0 && t_scaled < 0.0) || (det < 0.0 && t_scaled > 0.0) {
            return None;
        }
        let t = (t_scaled / det) as f32;
        t.is_finite().then_some(t)
    }

    /// The watertight test's common part: the corners moved to the ray's origin and
    /// sheared ([`RayShear`], made with the ray), the weights of a, b and c (each the edge
    /// value opposite that corner) and their sum, or `None` when the ray's line misses the
    /// triangle or the triangle is degenerate.
    #[inline]
    fn sheared_weights(&self, ray: &Ray3) -> Option<([Sheared; 3], [f64; 3], f64)> {
        let shear = ray.shear();
        let origin = ray.origin();
        let (a, b, c) = (
            shear.apply(self.a - origin),
            shear.apply(self.b - origin),
            shear.apply(self.c - origin),
        );

        // Edge functions in f64: a product of two f32 values is exact there, so each edge
        // value is rounded once, from that edge's two corners alone, and a shared edge gives
        // exactly negated values in its two triangles (watertightness). f64 also keeps them
        // from underflowing or overflowing at scales of 1e-20 or 1e20, where f32 products
        // would.
        let edge = |p: Sheared, q: Sheared| {
            f64::from(p.x) * f64::from(q.y) - f64::from(p.y) * f64::from(q.x)
        };
        // Two edge values of opposite signs already put the line outside, whatever the
        // third: the full test below refuses it too, so leaving early changes no answer (a
        // NaN fails both tests alike), and the WGSL mirror, which does not leave early,
        // still agrees bit for bit (tests/triangle_ray_exact.rs checks this against the full
        // test). Most rays that reach a leaf miss most of its triangles: this spares them a
        // third of the f64 work, 2-10% of the wide tree's first hits (issue 19, measured on
        // the bunny and the dragon).
        let (u, v) = (edge(c, b), edge(a, c));
        if (u < 0.0 && v > 0.0) || (u > 0.0 && v < 0.0) {
            return None;
        }
        let w = edge(b, a);
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || self.is_degenerate() {
            return None;
        }
        Some(([a, b, c], [u, v, w], det))
    }

    /// Where the ray crosses the triangle, as the barycentric coordinates `(u, v)` of
    /// Möller and Trumbore ("Fast, Minimum Storage Ray/Triangle Intersection", JGT 1997):
    /// the crossing is `(1 - u - v) a + u b + v c`, with `u, v >= 0` and `u + v <= 1`.
    /// `None` when [`ray_hit`](Self::ray_hit) finds no crossing.
    ///
    /// Computed from the same edge values as the watertight test (each edge's value is the
    /// scaled barycentric coordinate of the opposite corner), so a ray that hits gets
    /// coordinates inside the triangle, without a second, differently rounded test: what
    /// shading needs to interpolate normals and texture coordinates.
    pub fn ray_barycentric(&self, ray: &Ray3) -> Option<(f32, f32)> {
        let (_, [_, wb, wc], det) = self.sheared_weights(ray)?;
        Some(((wb / det) as f32, (wc / det) as f32))
    }

    /// The point of the triangle nearest to `p`.
    ///
    /// Voronoi-region method of Ericson, "Real-Time Collision Detection", §5.1.5: find which
    /// vertex, edge or face region `p` projects into using barycentric tests. A degenerate
    /// triangle falls back to the nearest of its three edges: an edge's region is taken only
    /// when its parameter's denominator is positive, which for `d1 >= 0 >= d3` (and the like)
    /// fails only when the edge has length 0 (its two ends one point: `0 / 0` was a NaN
    /// point, so brute force and every tree found such a triangle at a NaN distance).
    pub fn project_point(&self, p: Vec3) -> Vec3 {
        // In f64: at scales of 1e-20 the f32 dot products below would be subnormal and lose
        // the region decisions; products of f32 differences are (nearly) exact in f64.
        let (a, b, c, p) = (
            self.a.as_dvec3(),
            self.b.as_dvec3(),
            self.c.as_dvec3(),
            p.as_dvec3(),
        );
        let (ab, ac, ap) = (b - a, c - a, p - a);
        let (d1, d2) = (ab.dot(ap), ac.dot(ap));
        if d1 <= 0.0 && d2 <= 0.0 {
            return self.a;
        }
        let bp = p - b;
        let (d3, d4) = (ab.dot(bp), ac.dot(bp));
        if d3 >= 0.0 && d4 <= d3 {
            return self.b;
        }
        let vc = d1 * d4 - d3 * d2;
        if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
            return (a + ab * (d1 / (d1 - d3))).as_vec3();
        }
        let cp = p - c;
        let (d5, d6) = (ab.dot(cp), ac.dot(cp));
        if d6 >= 0.0 && d5 <= d6 {
            return self.c;
        }
        let vb = d5 * d2 - d1 * d6;
        if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
            return (a + ac * (d2 / (d2 - d6))).as_vec3();
        }
        let va = d3 * d6 - d5 * d4;
        if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0 {
            return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).as_vec3();
        }
        let sum = va + vb + vc;
        if sum > 0.0 && sum.is_finite() {
            // Inside the face region: barycentric coordinates (u, v, w) = (va, vb, vc) / sum.
            return (a + ab * (vb / sum) + ac * (vc / sum)).as_vec3();
        }
        self.closest_point_on_edges(p)
    }

    fn closest_point_on_edges(&self, p: DVec3) -> Vec3 {
        let on_edge = |s: Vec3, e: Vec3| {
            let (s, e) = (s.as_dvec3(), e.as_dvec3());
            let len2 = (e - s).length_squared();
            let t = if len2 > 0.0 {
                ((p - s).dot(e - s) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            s + (e - s) * t
        };
        [
            on_edge(self.a, self.b),
            on_edge(self.b, self.c),
            on_edge(self.c, self.a),
        ]
        .into_iter()
        .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
        .map_or(self.a, DVec3::as_vec3)
    }

    /// Whether the corners are collinear (zero area), decided on the `f64` cross product of
    /// the edges. Rounding in the ray's sheared frame can make such a triangle look thin but
    /// not flat; it has no interior to hit, so the ray test asks this first.
    #[inline]
    pub fn is_degenerate(&self) -> bool {
        let (a, b, c) = (self.a.as_dvec3(), self.b.as_dvec3(), self.c.as_dvec3());
        (b - a).cross(c - a) == DVec3::ZERO
    }

    /// The area.
    pub fn area(&self) -> f32 {
        0.5 * (self.b - self.a).cross(self.c - self.a).length()
    }

    /// The unit normal, or `None` for a degenerate triangle. Computed in `f64` so that thin
    /// triangles still get an accurate direction.
    pub fn unit_normal(&self) -> Option<Vec3> {
        let (a, b, c): (DVec3, DVec3, DVec3) =
            (self.a.as_dvec3(), self.b.as_dvec3(), self.c.as_dvec3());
        (b - a).cross(c - a).try_normalize().map(DVec3::as_vec3)
    }
}

impl Primitive for Triangle3 {
    type Point = Vec3;

    fn bounds(&self) -> Aabb<Vec3> {
        Aabb::new(
            self.a.min(self.b).min(self.c),
            self.a.max(self.b).max(self.c),
        )
    }
    fn centroid(&self) -> Vec3 {
        (self.a + self.b + self.c) / 3.0
    }
    #[inline]
    fn ray_hit(&self, ray: &Ray3) -> Option<f32> {
        Triangle3::ray_hit(self, ray)
    }
    /// [`Triangle3::ray_barycentric`]; `[0, 0]` (corner `a`) for a ray that misses.
    fn hit_coordinates(&self, ray: &Ray3, _t: f32) -> [f32; 2] {
        self.ray_barycentric(ray)
            .map_or([0.0, 0.0], |(u, v)| [u, v])
    }
    fn project_point(&self, point: Vec3) -> Vec3 {
        Triangle3::project_point(self, point)
    }
    fn measure(&self) -> f32 {
        self.area()
    }
    fn normal(&self) -> Vec3 {
        (self.b - self.a).cross(self.c - self.a)
    }
    fn intersects_aabb(&self, aabb: &Aabb<Vec3>) -> bool {
        super::overlap::triangle3_aabb(self, aabb)
    }
    fn intersects(&self, other: &Self) -> bool {
        super::overlap::triangle3_triangle3(self, other)
    }
    fn vertices(&self) -> impl Iterator<Item = Vec3> {
        [self.a, self.b, self.c].into_iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle3 {
        Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)
    }

    #[test]
    fn hits_from_both_sides_with_t_in_units_of_dir() {
        let down = Ray3::new(Vec3::new(0.2, 0.2, 1.0), Vec3::new(0.0, 0.0, -2.0)).expect("ray");
        assert_eq!(tri().ray_hit(&down), Some(0.5));
        let up = Ray3::new(Vec3::new(0.2, 0.2, -1.0), Vec3::Z).expect("ray");
        assert_eq!(tri().ray_hit(&up), Some(1.0));
        let away = Ray3::new(Vec3::new(0.2, 0.2, 1.0), Vec3::Z).expect("ray");
        assert_eq!(tri().ray_hit(&away), None);
    }

    #[test]
    fn a_repeated_vertex_projects_onto_the_other_edge() {
        // Each corner repeated in turn: the triangle is the segment from it to the third
        // corner, and every point projects onto that segment, never to NaN.
        let (p, q) = (Vec3::new(-3.0, 4.0, 3.0), Vec3::new(-4.0, 5.0, 2.0));
        let query = Vec3::new(-2.167_75, 6.843_661, -0.916_667);
        let on_segment = Segment3Like(p, q).project(query);
        for t in [
            Triangle3::new(p, p, q),
            Triangle3::new(p, q, p),
            Triangle3::new(q, p, p),
        ] {
            for point in [query, p, q, (p + q) * 0.5, Vec3::ZERO, p * 2.0 - q] {
                let got = t.project_point(point);
                assert!(got.is_finite(), "{t:?} projects {point} to {got}");
                let want = Segment3Like(p, q).project(point);
                assert!(
                    (got - want).length() < 1e-5,
                    "{t:?}: {point} to {got}, not {want}"
                );
            }
            assert!((t.project_point(query) - on_segment).length() < 1e-5);
        }
    }

    /// A segment in 3D, for the expected projections.
    struct Segment3Like(Vec3, Vec3);

    impl Segment3Like {
        fn project(&self, p: Vec3) -> Vec3 {
            let e = self.1 - self.0;
            self.0 + e * ((p - self.0).dot(e) / e.length_squared()).clamp(0.0, 1.0)
        }
    }

    #[test]
    fn ray_in_the_plane_and_degenerate_triangles_miss() {
        let grazing = Ray3::new(Vec3::new(-1.0, 0.1, 0.0), Vec3::X).expect("ray");
        assert_eq!(tri().ray_hit(&grazing), None);
        let flat = Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        let down = Ray3::new(Vec3::new(0.5, 0.0, 1.0), -Vec3::Z).expect("ray");
        assert_eq!(flat.ray_hit(&down), None);
        assert_eq!(
            flat.project_point(Vec3::new(0.5, 1.0, 0.0)),
            Vec3::new(0.5, 0.0, 0.0)
        );
    }

    #[test]
    fn closest_point_regions() {
        let t = tri();
        assert_eq!(t.project_point(Vec3::new(-1.0, -1.0, 3.0)), Vec3::ZERO);
        assert_eq!(
            t.project_point(Vec3::new(0.25, 0.25, 3.0)),
            Vec3::new(0.25, 0.25, 0.0)
        );
        assert_eq!(
            t.project_point(Vec3::new(0.5, -2.0, 0.0)),
            Vec3::new(0.5, 0.0, 0.0)
        );
        assert_eq!(
            t.project_point(Vec3::new(2.0, 2.0, 0.0)),
            Vec3::new(0.5, 0.5, 0.0)
        );
    }
}
