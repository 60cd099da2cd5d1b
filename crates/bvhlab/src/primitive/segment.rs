//! Line segments in 2D: ray-segment intersection and the closest point on a segment.

use glam::Vec2;

use super::Primitive;
use crate::Ray2;
use crate::volume::Aabb;

/// A line segment from `a` to `b` in the plane; a 2D scene is a slice of these.
///
/// A segment with `a == b` is a point: queries still answer (the closest point is `a`; a ray
/// hits it only when it passes exactly through it).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C)]
pub struct Segment2 {
    /// First end point.
    pub a: Vec2,
    /// Second end point.
    pub b: Vec2,
}

impl Segment2 {
    /// The segment from `a` to `b`.
    pub const fn new(a: Vec2, b: Vec2) -> Self {
        Self { a, b }
    }

    /// The smallest `t >= 0` at which the ray touches the segment, end points included.
    ///
    /// The test is the 2D analogue of Woop, Benthin and Wald's watertight ray-triangle test
    /// (JCGT 2013): each end point's side of the ray is the sign of `d × (p - e)`, computed
    /// from that end point alone, so two segments that share an end point agree on its side
    /// and a ray through the shared point hits at least one of them. A ray running along the
    /// segment hits it where it first touches it (at `t = 0` when it starts on it). Returns
    /// `None` for a ray whose coordinates are not all finite. Segment/line intersection as in
    /// Ericson, "Real-Time Collision Detection", §5.1.9.
    pub fn ray_hit(&self, ray: &Ray2) -> Option<f32> {
        let (o, d) = (ray.origin().as_dvec2(), ray.dir().as_dvec2());
        // End points relative to the origin in f64: exact for f32 inputs of similar
        // magnitude, and, what watertightness needs, a function of that end point alone.
        let (pa, pb) = (self.a.as_dvec2() - o, self.b.as_dvec2() - o);
        let (side_a, side_b) = (d.perp_dot(pa), d.perp_dot(pb));
        if (side_a > 0.0 && side_b > 0.0) || (side_a < 0.0 && side_b < 0.0) {
            return None;
        }
        let len2 = d.length_squared();
        // Where the ray passes each end point's projection: the hit lies between them.
        let (ta, tb) = (d.dot(pa) / len2, d.dot(pb) / len2);
        let t = if side_a == 0.0 && side_b == 0.0 {
            // Both on the ray's line (both zero): the ray enters at the nearer end, or at t = 0
            // when it starts on the segment.
            let (near, far) = (ta.min(tb), ta.max(tb));
            if far < 0.0 {
                return None;
            }
            near.max(0.0)
        } else {
            // The crossing divides the segment in the ratio of the end points' distances to
            // the ray's line; t is the same convex combination of ta and tb, so it stays on the
            // segment even for grazing rays far from the origin.
            let s = side_a / (side_a - side_b);
            ta + (tb - ta) * s
        };
        (t >= 0.0 && t.is_finite()).then_some(t as f32)
    }

    /// Where on the segment a hit at `t` lies: the parameter `u` in `[0, 1]` with the hit at
    /// `a + u (b - a)` (0 at `a`, 1 at `b`). A ray crossing the segment gets the ratio of
    /// its end points' distances to the ray's line (the crossing [`ray_hit`](Self::ray_hit)
    /// computes); a ray along it, the projection of `ray.at(t)`. 0 for a zero-length segment.
    pub fn hit_parameter(&self, ray: &Ray2, t: f32) -> f32 {
        let (o, d) = (ray.origin().as_dvec2(), ray.dir().as_dvec2());
        let (pa, pb) = (self.a.as_dvec2() - o, self.b.as_dvec2() - o);
        let (side_a, side_b) = (d.perp_dot(pa), d.perp_dot(pb));
        let s = if side_a != side_b && (side_a - side_b).is_finite() {
            side_a / (side_a - side_b)
        } else {
            let e = pb - pa;
            let len2 = e.length_squared();
            if len2 == 0.0 {
                return 0.0;
            }
            (d * f64::from(t) - pa).dot(e) / len2
        };
        if s.is_nan() {
            0.0
        } else {
            s.clamp(0.0, 1.0) as f32
        }
    }

    /// The point of the segment nearest to `p`: the projection of `p` on the line, clamped to
    /// the segment (Ericson, "Real-Time Collision Detection", §5.1.2).
    pub fn project_point(&self, p: Vec2) -> Vec2 {
        // In f64, so that tiny (1e-20) coordinates do not make the dot products subnormal.
        let (a, e) = (self.a.as_dvec2(), (self.b.as_dvec2() - self.a.as_dvec2()));
        let len2 = e.length_squared();
        if len2 == 0.0 {
            return self.a;
        }
        let s = ((p.as_dvec2() - a).dot(e) / len2).clamp(0.0, 1.0);
        (a + e * s).as_vec2()
    }

    /// The segment's length.
    pub fn length(&self) -> f32 {
        (self.b - self.a).length()
    }
}

impl Primitive for Segment2 {
    type Point = Vec2;

    fn bounds(&self) -> Aabb<Vec2> {
        Aabb::new(self.a.min(self.b), self.a.max(self.b))
    }
    fn centroid(&self) -> Vec2 {
        (self.a + self.b) * 0.5
    }
    fn ray_hit(&self, ray: &Ray2) -> Option<f32> {
        Segment2::ray_hit(self, ray)
    }
    /// `[u, 0]`, with `u` the parameter along the segment ([`Segment2::hit_parameter`]).
    fn hit_coordinates(&self, ray: &Ray2, t: f32) -> [f32; 2] {
        [self.hit_parameter(ray, t), 0.0]
    }
    fn project_point(&self, point: Vec2) -> Vec2 {
        Segment2::project_point(self, point)
    }
    fn measure(&self) -> f32 {
        self.length()
    }
    fn normal(&self) -> Vec2 {
        let e = self.b - self.a;
        Vec2::new(e.y, -e.x)
    }
    fn intersects_aabb(&self, aabb: &Aabb<Vec2>) -> bool {
        super::overlap::segment2_aabb(self, aabb)
    }
    fn intersects(&self, other: &Self) -> bool {
        super::overlap::segment2_segment2(self, other)
    }
    fn vertices(&self) -> impl Iterator<Item = Vec2> {
        [self.a, self.b].into_iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: (f32, f32), d: (f32, f32)) -> Ray2 {
        Ray2::new(Vec2::new(o.0, o.1), Vec2::new(d.0, d.1)).expect("valid test ray")
    }

    #[test]
    fn crossing_ray_hits_at_the_crossing() {
        let s = Segment2::new(Vec2::new(2.0, -1.0), Vec2::new(2.0, 1.0));
        assert_eq!(s.ray_hit(&ray((0.0, 0.0), (1.0, 0.0))), Some(2.0));
        assert_eq!(s.ray_hit(&ray((0.0, 0.0), (2.0, 0.0))), Some(1.0));
        assert_eq!(s.ray_hit(&ray((3.0, 0.0), (1.0, 0.0))), None);
    }

    #[test]
    fn ray_along_the_segment_hits_its_near_end() {
        let s = Segment2::new(Vec2::new(2.0, 0.0), Vec2::new(4.0, 0.0));
        assert_eq!(s.ray_hit(&ray((0.0, 0.0), (1.0, 0.0))), Some(2.0));
        assert_eq!(s.ray_hit(&ray((3.0, 0.0), (1.0, 0.0))), Some(0.0));
        assert_eq!(s.ray_hit(&ray((5.0, 0.0), (1.0, 0.0))), None);
    }

    #[test]
    fn project_point_clamps_to_the_ends() {
        let s = Segment2::new(Vec2::ZERO, Vec2::new(2.0, 0.0));
        assert_eq!(s.project_point(Vec2::new(-1.0, 1.0)), Vec2::ZERO);
        assert_eq!(s.project_point(Vec2::new(1.0, 1.0)), Vec2::new(1.0, 0.0));
        assert_eq!(
            Segment2::new(Vec2::ONE, Vec2::ONE).project_point(Vec2::ZERO),
            Vec2::ONE
        );
    }
}
