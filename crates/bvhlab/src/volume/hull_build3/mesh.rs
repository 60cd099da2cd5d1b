//! Quickhull's mesh: triangles with their neighbours, grown one eye point at a time.

use glam::{DVec3, Vec3};

use super::SKEW;
use crate::Triangle3;
use crate::volume::ConvexHull;
use crate::volume::hull::predicates::{accurate_cross, orient3d};

/// "No face" in an adjacency slot, "no edge" in `horizon_from`.
const NONE: u32 = u32::MAX;

/// A triangle of the hull under construction.
struct Face {
    /// Corners, counter-clockwise seen from outside.
    corners: [u32; 3],
    /// `neighbours[i]` is the face across the edge `corners[i] → corners[i + 1]`.
    neighbours: [u32; 3],
    /// Outward unit normal and plane offset: a point `p` is `normal · p − offset` above it.
    normal: DVec3,
    offset: f64,
    /// The points above this face (and assigned to it).
    outside: Vec<u32>,
    alive: bool,
    /// The last round in which the eye saw this face.
    seen_in: u32,
    /// The last round in which the eye was found not to see this face.
    hidden_in: u32,
}

/// Quickhull's state: the mesh, free face slots, and per-round marks.
pub(super) struct Quickhull {
    points: Vec<DVec3>,
    /// The bound on the rounding error of a height (see the module documentation).
    margin: f64,
    faces: Vec<Face>,
    free: Vec<u32>,
    /// Faces that may have outside points (checked again when popped).
    pending: Vec<u32>,
    /// The round in which each point became a corner of the visible region.
    in_region: Vec<u32>,
    /// During horizon extraction: the horizon edge starting at each point.
    horizon_from: Vec<u32>,
    round: u32,
}

impl Quickhull {
    pub(super) fn new(points: Vec<DVec3>, [a, b, c, d]: [usize; 4]) -> Self {
        let n = points.len();
        let reach = points.iter().fold(DVec3::ZERO, |m, p| m.max(p.abs()));
        let mut hull = Self {
            points,
            margin: 64.0 * f64::EPSILON * reach.element_sum(),
            faces: Vec::new(),
            free: Vec::new(),
            pending: Vec::new(),
            in_region: vec![0; n],
            horizon_from: vec![NONE; n],
            round: 0,
        };
        let [a, b, c, d] = [a, b, c, d].map(|i| i as u32);
        let tetra = [[a, b, c], [a, d, b], [b, d, c], [c, d, a]];
        for corners in tetra {
            hull.add_face(corners);
        }
        // Each edge of one face is the reversed edge of exactly one other.
        for (f, corners) in tetra.iter().enumerate() {
            for e in 0..3 {
                let (p, q) = (corners[e], corners[(e + 1) % 3]);
                let twin = tetra
                    .iter()
                    .position(|other| (0..3).any(|k| other[k] == q && other[(k + 1) % 3] == p));
                hull.faces[f].neighbours[e] = twin.map_or(NONE, |g| g as u32);
            }
        }
        let rest: Vec<u32> = (0..n as u32)
            .filter(|i| ![a, b, c, d].contains(i))
            .collect();
        hull.assign(&rest, &[0, 1, 2, 3]);
        hull
    }

    /// Adds a face (reusing a free slot), its plane through its corners' centroid.
    fn add_face(&mut self, corners: [u32; 3]) -> u32 {
        let [a, b, c] = corners.map(|i| self.points[i as usize]);
        let normal = accurate_cross(a, b, c).normalize_or_zero();
        let face = Face {
            corners,
            neighbours: [NONE; 3],
            normal,
            offset: normal.dot((a + b + c) / 3.0),
            outside: Vec::new(),
            alive: true,
            seen_in: 0,
            hidden_in: 0,
        };
        if let Some(slot) = self.free.pop() {
            self.faces[slot as usize] = face;
            slot
        } else {
            self.faces.push(face);
            (self.faces.len() - 1) as u32
        }
    }

    /// The mesh's corners and its number of vertices. A corner is a vertex whose triangles
    /// lie in at least three planes; one whose triangles lie in one plane (inside a flat side)
    /// or two (on an edge) is not a corner of the hull. Quickhull can leave such vertices
    /// behind when points are coplanar: the point farthest above a face is a corner of what
    /// has been seen so far, but points seen later can put it on a flat side.
    pub(super) fn corners(&self) -> (Vec<u32>, usize) {
        let mut incident: Vec<(u32, u32)> = (0..self.faces.len() as u32)
            .filter(|&f| self.faces[f as usize].alive)
            .flat_map(|f| self.faces[f as usize].corners.map(|c| (c, f)))
            .collect();
        incident.sort_unstable();
        let stars: Vec<&[(u32, u32)]> = incident.chunk_by(|x, y| x.0 == y.0).collect();
        let corners = stars
            .iter()
            .filter(|star| {
                let faces: Vec<u32> = star.iter().map(|&(_, f)| f).collect();
                self.spans_three_planes(&faces)
            })
            .map(|star| star[0].0)
            .collect();
        (corners, stars.len())
    }

    fn spans_three_planes(&self, faces: &[u32]) -> bool {
        // Faces whose accurate normals clearly differ are not coplanar; others are checked
        // exactly.
        let coplanar = |f: u32, g: u32| {
            let (face, other) = (&self.faces[f as usize], &self.faces[g as usize]);
            f == g
                || face.normal.dot(other.normal) > 1.0 - 1e-9
                    && other.corners.iter().all(|&p| self.side(f, p) == 0.0)
        };
        let Some(&first) = faces.first() else {
            return false;
        };
        let Some(&second) = faces.iter().find(|&&g| !coplanar(first, g)) else {
            return false;
        };
        faces
            .iter()
            .any(|&g| !coplanar(first, g) && !coplanar(second, g))
    }

    /// Which side of face `f` point `p` is on: positive above, negative below, zero on its
    /// plane. By its height when that is clearly positive or negative, else exactly.
    fn side(&self, f: u32, p: u32) -> f64 {
        let face = &self.faces[f as usize];
        let x = self.points[p as usize];
        let height = face.height(x);
        if height.abs() > self.margin {
            return height;
        }
        let [a, b, c] = face.corners.map(|i| self.points[i as usize]);
        orient3d(a, b, c, x)
    }

    /// Whether point `p` is strictly above face `f`.
    fn is_above(&self, f: u32, p: u32) -> bool {
        self.side(f, p) > 0.0
    }

    /// Gives each point to the first of `faces` it is above; the others are inside the hull
    /// (or on it) for good.
    fn assign(&mut self, points: &[u32], faces: &[u32]) {
        for &p in points {
            if let Some(&f) = faces.iter().find(|&&f| self.is_above(f, p)) {
                let face = &mut self.faces[f as usize];
                face.outside.push(p);
                if face.outside.len() == 1 {
                    self.pending.push(f);
                }
            }
        }
    }

    /// Adds eye points until no face has points above it.
    pub(super) fn run(&mut self) {
        while let Some(f) = self.pending.pop() {
            let face = &self.faces[f as usize];
            if !face.alive {
                continue;
            }
            // The farthest point; among points as far to within rounding (coplanar input), the
            // one farthest along a fixed skew direction, which is a corner of their face.
            let height = |p: u32| face.height(self.points[p as usize]);
            let top = face
                .outside
                .iter()
                .map(|&p| height(p))
                .fold(f64::NEG_INFINITY, f64::max);
            let skew = |p: u32| SKEW.dot(self.points[p as usize]);
            let eye = face
                .outside
                .iter()
                .copied()
                .filter(|&p| height(p) >= top - 2.0 * self.margin)
                .max_by(|&p, &q| skew(p).total_cmp(&skew(q)));
            if let Some(eye) = eye {
                self.add_point(f, eye);
                self.pending.push(f); // Still alive if the eye had to be dropped.
            }
        }
    }

    /// Replaces the faces `eye` sees (a disk around `start`) by a cone from `eye` to their
    /// boundary, the horizon.
    fn add_point(&mut self, start: u32, eye: u32) {
        self.round += 1;
        let region = self.visible_region(start, eye);
        let Some(horizon) = self.horizon(&region) else {
            // Cannot happen for a disk; should it ever, drop the eye rather than break the mesh.
            self.faces[start as usize].outside.retain(|&p| p != eye);
            return;
        };
        let mut orphans = Vec::new();
        for &f in &region {
            let face = &mut self.faces[f as usize];
            orphans.append(&mut face.outside);
            face.alive = false;
            self.free.push(f);
        }
        let cone: Vec<u32> = horizon
            .iter()
            .map(|&(a, b, _)| self.add_face([a, b, eye]))
            .collect();
        let k_max = cone.len();
        for (k, &(_, b, beyond)) in horizon.iter().enumerate() {
            let (this, next, previous) = (
                cone[k],
                cone[(k + 1) % k_max],
                cone[(k + k_max - 1) % k_max],
            );
            self.faces[this as usize].neighbours = [beyond, next, previous];
            // The face beyond the horizon now borders the new face along b → a.
            let outer = &mut self.faces[beyond as usize];
            if let Some(e) = (0..3).find(|&e| outer.corners[e] == b) {
                outer.neighbours[e] = this;
            }
        }
        orphans.retain(|&p| p != eye);
        self.assign(&orphans, &cone);
    }

    /// The faces that `eye` is above, grown breadth-first from `start` over shared edges, each
    /// admitted only if the region stays a disk (see [`Self::keeps_disk`]).
    fn visible_region(&mut self, start: u32, eye: u32) -> Vec<u32> {
        let round = self.round;
        let mut region = vec![start];
        self.admit(start);
        let mut next = 0;
        while let Some(&f) = region.get(next) {
            next += 1;
            for e in 0..3 {
                let g = self.faces[f as usize].neighbours[e];
                let face = &self.faces[g as usize];
                if face.seen_in == round || face.hidden_in == round {
                    continue;
                }
                if !self.is_above(g, eye) {
                    self.faces[g as usize].hidden_in = round;
                } else if self.keeps_disk(g) {
                    self.admit(g);
                    region.push(g);
                }
                // Otherwise it may be admitted later, reached over another edge.
            }
        }
        region
    }

    fn admit(&mut self, f: u32) {
        let face = &mut self.faces[f as usize];
        face.seen_in = self.round;
        for &c in &face.corners {
            self.in_region[c as usize] = self.round;
        }
    }

    /// Whether adding face `f` to the visible region (a disk) leaves a disk: across one shared
    /// edge its third corner must be new to the region (else the region would pinch or close
    /// around a hole); across two shared edges it fills a notch; across three it would
    /// swallow the whole mesh.
    fn keeps_disk(&self, f: u32) -> bool {
        let face = &self.faces[f as usize];
        let shared = face
            .neighbours
            .map(|g| self.faces[g as usize].seen_in == self.round);
        let is_new = |corner: u32| self.in_region[corner as usize] != self.round;
        match shared {
            [true, false, false] => is_new(face.corners[2]),
            [false, true, false] => is_new(face.corners[0]),
            [false, false, true] => is_new(face.corners[1]),
            [true, true, true] => false,
            _ => true,
        }
    }

    /// The region's boundary as one loop of edges `(a, b, face beyond)`, in order (`b` of one
    /// is `a` of the next), or `None` if it is not one simple loop.
    fn horizon(&mut self, region: &[u32]) -> Option<Vec<(u32, u32, u32)>> {
        let mut edges = Vec::new();
        for &f in region {
            let face = &self.faces[f as usize];
            for e in 0..3 {
                let beyond = face.neighbours[e];
                if self.faces[beyond as usize].seen_in != self.round {
                    edges.push((face.corners[e], face.corners[(e + 1) % 3], beyond));
                }
            }
        }
        let mut simple = !edges.is_empty();
        for (k, &(a, ..)) in edges.iter().enumerate() {
            simple &= self.horizon_from[a as usize] == NONE;
            self.horizon_from[a as usize] = k as u32;
        }
        // Walk from edge 0: a simple loop comes back to it after visiting every edge once.
        let mut ordered = Vec::with_capacity(edges.len());
        let mut k = 0;
        while simple {
            ordered.push(edges[k]);
            k = self.horizon_from[edges[k].1 as usize] as usize;
            simple = k != 0 && k < edges.len() && ordered.len() < edges.len();
        }
        for &(a, ..) in &edges {
            self.horizon_from[a as usize] = NONE;
        }
        let closed = k == 0 && !edges.is_empty() && ordered.len() == edges.len();
        closed.then_some(ordered)
    }

    /// The finished hull: the live faces as triangles of input points, and the points they use.
    pub(super) fn into_hull(self, input: &[Vec3]) -> ConvexHull<Vec3> {
        let live: Vec<&Face> = self.faces.iter().filter(|f| f.alive).collect();
        let mut used: Vec<u32> = live.iter().flat_map(|f| f.corners).collect();
        used.sort_unstable();
        used.dedup();
        let vertices = used.iter().map(|&i| input[i as usize]).collect();
        let facets = live
            .iter()
            .map(|f| {
                let [a, b, c] = f.corners.map(|i| input[i as usize]);
                Triangle3::new(a, b, c)
            })
            .collect();
        ConvexHull::from_parts(vertices, facets, Some(3))
    }
}

impl Face {
    fn height(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}
