//! The lecture's "collision query with OOBBs" in 3D: two oriented boxes the student places
//! and turns by typed numbers (or puts on a brushed part's PCA box), tested by the core's
//! separating-axis test with its 15 candidate axes, stepped axis by axis.

use bvhlab::glam::{EulerRot, Mat3, Quat, Vec3};
use bvhlab::volume::{AxisSource, AxisTest};
use bvhlab::{BoundingVolume, Obb3};

/// One box: where it is, its size and how it is turned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxPose3 {
    /// Centre.
    pub center: Vec3,
    /// Half extents along the box's own axes.
    pub half: Vec3,
    /// The turn, as angles in degrees about x, then y, then z (each about the axes already
    /// turned: intrinsic x-y-z Euler angles).
    pub degrees: Vec3,
}

impl BoxPose3 {
    /// The turn as a rotation.
    pub fn rotation(&self) -> Quat {
        let r = self.degrees * (std::f32::consts::PI / 180.0);
        Quat::from_euler(EulerRot::XYZ, r.x, r.y, r.z)
    }

    /// The oriented box.
    pub fn obb(&self) -> Obb3 {
        let m = Mat3::from_quat(self.rotation());
        Obb3::new(self.center, [m.x_axis, m.y_axis, m.z_axis], self.half)
    }

    /// The pose of `obb` (its axes must be a right-handed orthonormal frame, as the core's
    /// fits give); `None` for an empty or non-finite box.
    pub fn of_obb(obb: &Obb3) -> Option<Self> {
        if obb.is_empty() || !obb.center.is_finite() || !obb.half_extents.is_finite() {
            return None;
        }
        let [u, v, w] = obb.axes;
        let (x, y, z) = Quat::from_mat3(&Mat3::from_cols(u, v, w))
            .normalize()
            .to_euler(EulerRot::XYZ);
        let pose = Self {
            center: obb.center,
            half: obb.half_extents,
            degrees: Vec3::new(x, y, z) * (180.0 / std::f32::consts::PI),
        };
        pose.is_valid().then_some(pose)
    }

    /// Whether the pose makes a box: finite numbers, half extents not negative.
    pub fn is_valid(&self) -> bool {
        self.center.is_finite()
            && self.half.is_finite()
            && self.degrees.is_finite()
            && self.half.min_element() >= 0.0
    }
}

/// The two boxes, and which of the candidate axes the student is looking at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObbPair3 {
    /// Box A.
    pub a: BoxPose3,
    /// Box B.
    pub b: BoxPose3,
    /// The candidate looked at, an index into [`CANDIDATES`].
    pub step: usize,
}

/// The 15 candidate axes in the lecture's (and the core's) order: A's three face normals,
/// B's three, then the nine edge pairs `A_i × B_j`, row by row.
pub const CANDIDATES: [AxisSource; 15] = {
    let mut all = [AxisSource::FaceA(0); 15];
    let mut k = 0;
    while k < 3 {
        all[k] = AxisSource::FaceA(k);
        all[3 + k] = AxisSource::FaceB(k);
        k += 1;
    }
    let mut ij = 0;
    while ij < 9 {
        all[6 + ij] = AxisSource::Edges(ij / 3, ij % 3);
        ij += 1;
    }
    all
};

impl ObbPair3 {
    /// A pair about `center`, `size` across, overlapping a little and turned so that an edge
    /// pair matters.
    pub fn around(center: Vec3, size: f32) -> Self {
        Self {
            a: BoxPose3 {
                center: center - Vec3::new(size * 0.45, 0.0, 0.0),
                half: Vec3::new(0.5, 0.25, 0.2) * size,
                degrees: Vec3::new(0.0, 0.0, 20.0),
            },
            b: BoxPose3 {
                center: center + Vec3::new(size * 0.45, size * 0.1, 0.0),
                half: Vec3::new(0.3, 0.3, 0.25) * size,
                degrees: Vec3::new(30.0, 40.0, 0.0),
            },
            step: 0,
        }
    }

    /// Whether both boxes are valid and the step names a candidate.
    pub fn is_valid(&self) -> bool {
        self.a.is_valid() && self.b.is_valid() && self.step < CANDIDATES.len()
    }

    /// The core's test on each candidate, in [`CANDIDATES`]' order; `None` where the core
    /// leaves an edge pair out because the two edges are (nearly) parallel (their cross
    /// product has no direction, and a face axis already decides).
    pub fn tests(&self) -> [Option<AxisTest<Vec3>>; 15] {
        let tests = self.a.obb().sat_tests(&self.b.obb());
        CANDIDATES.map(|source| tests.iter().find(|t| t.source == source).copied())
    }

    /// The core's answer: the first axis that separates the boxes, `None` when they overlap.
    pub fn separating(&self) -> Option<AxisSource> {
        self.a
            .obb()
            .separating_axis(&self.b.obb())
            .map(|s| s.source)
    }
}

/// A candidate's name, the same in the table, the sentence under it and the view's legend:
/// "A face 0" is the normal of A's face 0, "A0 × B2" the cross product of A's edge 0 and
/// B's edge 2.
pub fn axis_name(source: AxisSource) -> String {
    match source {
        AxisSource::FaceA(i) => format!("A face {i}"),
        AxisSource::FaceB(j) => format!("B face {j}"),
        AxisSource::Edges(i, j) => format!("A{i} × B{j}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_keeps_its_pose_through_its_obb() {
        let pose = BoxPose3 {
            center: Vec3::new(1.0, -2.0, 3.0),
            half: Vec3::new(0.5, 1.0, 2.0),
            degrees: Vec3::new(10.0, -35.0, 70.0),
        };
        let back = BoxPose3::of_obb(&pose.obb()).expect("a box");
        assert!(
            (back.degrees - pose.degrees).abs().max_element() < 1e-3,
            "{back:?}"
        );
        assert_eq!(back.center, pose.center);
        assert_eq!(back.half, pose.half);
    }

    #[test]
    fn the_candidates_are_the_cores_order_and_a_parallel_edge_pair_is_left_out() {
        let mut pair = ObbPair3::around(Vec3::ZERO, 2.0);
        let core: Vec<AxisSource> = pair
            .a
            .obb()
            .sat_tests(&pair.b.obb())
            .iter()
            .map(|t| t.source)
            .collect();
        assert_eq!(core, CANDIDATES.to_vec(), "turned boxes: all 15");
        // Both turned only about z: A's z edge is parallel to B's.
        pair.a.degrees = Vec3::new(0.0, 0.0, 20.0);
        pair.b.degrees = Vec3::new(0.0, 0.0, 50.0);
        let tests = pair.tests();
        let left_out: Vec<AxisSource> = CANDIDATES
            .iter()
            .zip(&tests)
            .filter(|(_, t)| t.is_none())
            .map(|(s, _)| *s)
            .collect();
        assert!(left_out.contains(&AxisSource::Edges(2, 2)), "{left_out:?}");
        pair.b.center = pair.a.center + Vec3::new(100.0, 0.0, 0.0);
        assert!(pair.separating().is_some());
        pair.b.center = pair.a.center;
        assert_eq!(pair.separating(), None);
    }
}
