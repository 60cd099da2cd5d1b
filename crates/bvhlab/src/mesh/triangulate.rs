//! Polygon faces to triangles: ear clipping in the polygon's plane.
//!
//! Every simple polygon with more than three corners has an ear, a corner whose triangle with
//! its two neighbours lies inside the polygon (Meisters, "Polygons Have Ears", American
//! Mathematical Monthly 82(6), 1975); cutting ears one at a time triangulates it (Eberly,
//! "Triangulation by Ear Clipping", Geometric Tools, 2002). Unlike a fan from the first
//! corner, this is right for concave faces too. A face of `n` corners always gives `n − 2`
//! triangles in the face's winding: a face that is not a simple polygon (self-crossing, or
//! with all corners on a line) is finished as a fan, as are faces of more than
//! [`MAX_EAR_CLIPPING`] corners, for which the quadratic search would be slow.

use glam::{DVec2, DVec3, Vec3};

/// Faces with more corners than this are fanned rather than ear-clipped.
pub(super) const MAX_EAR_CLIPPING: usize = 256;

/// Appends the triangles of the face `corners` (indices into `positions`, all valid).
pub(super) fn triangulate(corners: &[u32], positions: &[Vec3], out: &mut Vec<[u32; 3]>) {
    match corners {
        [] | [_] | [_, _] => {}
        &[a, b, c] => out.push([a, b, c]),
        _ if corners.len() > MAX_EAR_CLIPPING => fan(corners, out),
        _ => match plane_coordinates(corners, positions) {
            Some(points) => clip_ears(corners, &points, out),
            None => fan(corners, out),
        },
    }
}

/// Triangles `(c₀, cᵢ, cᵢ₊₁)`.
fn fan(corners: &[u32], out: &mut Vec<[u32; 3]>) {
    for pair in corners[1..].windows(2) {
        out.push([corners[0], pair[0], pair[1]]);
    }
}

/// The corners projected onto the coordinate plane most nearly parallel to the face, oriented
/// so that the face runs counter-clockwise; `None` for a face with no area.
///
/// The face's normal is Newell's (Sutherland, Sproull and Schumacker, "A Characterization of
/// Ten Hidden-Surface Algorithms", Computing Surveys 6(1), 1974): the sum of the cross
/// products of consecutive corners, exact for planar faces and a good average otherwise.
fn plane_coordinates(corners: &[u32], positions: &[Vec3]) -> Option<Vec<DVec2>> {
    let at = |i: usize| positions[corners[i] as usize].as_dvec3();
    let origin = at(0);
    let n = corners.len();
    let normal: DVec3 = (0..n)
        .map(|i| (at(i) - origin).cross(at((i + 1) % n) - origin))
        .sum();
    let k = normal.abs().max_position();
    if normal[k] == 0.0 || !normal.is_finite() {
        return None;
    }
    // Dropping axis k and keeping (k + 1, k + 2) in cyclic order looks at the face from +k.
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let flip = if normal[k] > 0.0 { 1.0 } else { -1.0 };
    Some(
        (0..n)
            .map(|i| {
                let p = at(i) - origin;
                DVec2::new(p[u], flip * p[v])
            })
            .collect(),
    )
}

/// `(b − a) × (c − a)`: positive when `a, b, c` turn counter-clockwise.
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Cuts ears off the counter-clockwise polygon `points` (the projected `corners`).
fn clip_ears(corners: &[u32], points: &[DVec2], out: &mut Vec<[u32; 3]>) {
    let mut left: Vec<usize> = (0..corners.len()).collect();
    while left.len() > 3 {
        let m = left.len();
        // Trying corner 1 first makes a convex face come out as the fan from corner 0.
        let ear = (1..m).chain(0..1).find(|&i| {
            let (p, c, n) = (left[(i + m - 1) % m], left[i], left[(i + 1) % m]);
            let (a, b, d) = (points[p], points[c], points[n]);
            orient(a, b, d) > 0.0
                && left.iter().all(|&q| {
                    let x = points[q];
                    // Corners of the ear, and corners repeated at the same place, do not block.
                    x == a
                        || x == b
                        || x == d
                        || orient(a, b, x) < 0.0
                        || orient(b, d, x) < 0.0
                        || orient(d, a, x) < 0.0
                })
        });
        let Some(i) = ear else {
            // Not a simple polygon: finish with a fan of what is left.
            let rest: Vec<u32> = left.iter().map(|&i| corners[i]).collect();
            fan(&rest, out);
            return;
        };
        let (p, c, n) = (left[(i + m - 1) % m], left[i], left[(i + 1) % m]);
        out.push([corners[p], corners[c], corners[n]]);
        left.remove(i);
    }
    out.push([corners[left[0]], corners[left[1]], corners[left[2]]]);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(points: &[[f32; 3]]) -> Vec<[u32; 3]> {
        let positions: Vec<Vec3> = points.iter().map(|&p| Vec3::from(p)).collect();
        let corners: Vec<u32> = (0..positions.len() as u32).collect();
        let mut out = Vec::new();
        triangulate(&corners, &positions, &mut out);
        assert_eq!(out.len(), positions.len() - 2);
        out
    }

    #[test]
    fn a_concave_face_is_cut_inside_itself() {
        // A dart with its notch at corner 1: the fan from corner 0 would use the diagonal
        // 0–2, which runs outside the face, and give a clockwise triangle.
        let dart = [
            [4.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 4.0, 0.0],
            [0.0, 0.0, 0.0],
        ];
        let mut area = 0.0;
        for [a, b, c] in run(&dart) {
            let p = |i: u32| Vec3::from(dart[i as usize]);
            let z = (p(b) - p(a)).cross(p(c) - p(a)).z;
            assert!(z > 0.0, "triangle {a} {b} {c} is clockwise");
            area += z / 2.0;
        }
        // Shoelace: the dart's area is 4.
        assert_eq!(area, 4.0);
    }

    #[test]
    fn clockwise_faces_in_any_plane_keep_their_winding() {
        let quad = [
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 2.0],
            [0.0, 2.0, 2.0],
            [0.0, 2.0, 0.0],
        ];
        for [a, b, c] in run(&quad) {
            let p = |i: u32| Vec3::from(quad[i as usize]);
            assert!((p(b) - p(a)).cross(p(c) - p(a)).x < 0.0);
        }
    }

    #[test]
    fn degenerate_faces_still_give_n_minus_2_triangles() {
        run(&[[0.0, 0.0, 0.0]; 5]);
        run(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
        ]);
        // A bow tie (self-crossing).
        run(&[
            [0.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
        ]);
    }
}
