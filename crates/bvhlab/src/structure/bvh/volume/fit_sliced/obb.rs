//! The OBB-tree node fit ([`Obb::pca_fit`], then the growth and checks of `volume/obb.rs`) in
//! four resumable passes over the node's vertices: the mean, the covariance (whose
//! eigenvectors are the box's axes), the extremes along the axes (which place the centre),
//! and the half extents measured as `contains` measures them. A fifth pass checks
//! containment for coordinates beyond [`HUGE`], as the one-go fit does.
//!
//! Every sum and fold is the one-go fit's, in the same order and precision (`f64` for the
//! mean and covariance, `f32` in the box's frame), so the box is the same to the bit.

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::Cursor;
use crate::Vector;
use crate::math::eigen::symmetric_eigen;
use crate::structure::bvh::volume::{HUGE, growth, magnitude};
use crate::volume::{Aabb, BoundingVolume, Obb};

/// The PCA box of a node's vertices, a chunk of points at a time.
#[derive(Clone, Debug)]
pub(in crate::structure::bvh) struct PcaBoxPasses<V: Vector> {
    /// Whether the node's coordinates exceed [`HUGE`], so that the box must be checked
    /// against every vertex.
    huge: bool,
    cursor: Cursor,
    pass: Pass<V>,
}

#[derive(Clone, Copy, Debug)]
enum Pass<V: Vector> {
    /// Summing the points, in `f64`.
    Mean([f64; 3]),
    /// Summing the products of the centred coordinates.
    Covariance {
        mean: [f64; 3],
        cov: [[f64; 3]; 3],
    },
    /// The extremes of the points along the axes, relative to the mean.
    Extremes {
        frame: Obb<V>,
        lo: V,
        hi: V,
    },
    /// The half extents around the centre placed between the extremes.
    HalfExtents {
        obb: Obb<V>,
        half: V,
    },
    /// Checking that the grown box holds every vertex (huge coordinates only).
    Contains(Obb<V>),
    Done(Obb<V>),
}

impl<V: Vector> PcaBoxPasses<V> {
    /// The fit of a node with bounds `bounds`, before its first pass.
    pub fn new(bounds: &Aabb<V>) -> Self {
        Self {
            huge: magnitude(bounds.min).max(magnitude(bounds.max)) > HUGE,
            cursor: Cursor::default(),
            pass: Pass::Mean([0.0; 3]),
        }
    }

    /// The box, once every pass is done.
    pub fn result(&self) -> Option<Obb<V>> {
        match self.pass {
            Pass::Done(obb) => Some(obb),
            _ => None,
        }
    }

    /// Reads about `units` points (at least one) or until the box is done; returns how many
    /// were read.
    pub fn advance(&mut self, points: &[V], units: usize) -> usize {
        let units = units.max(1);
        let mut read = 0;
        while read < units && self.result().is_none() {
            if self.cursor.at_end(points) {
                self.pass = self.next_pass(points.len());
                self.cursor = Cursor::default();
                continue;
            }
            let chunk = self.cursor.chunk(points, units - read);
            read += chunk.len();
            self.read(chunk);
        }
        read
    }

    /// One chunk of the current pass.
    fn read(&mut self, chunk: &[V]) {
        match &mut self.pass {
            Pass::Mean(sum) => {
                for p in chunk {
                    for (s, x) in sum.iter_mut().zip(p.to_dvec3().to_array()).take(V::DIM) {
                        *s += x;
                    }
                }
            }
            Pass::Covariance { mean, cov } => {
                for p in chunk {
                    let p = p.to_dvec3().to_array();
                    let d: [f64; 3] = std::array::from_fn(|i| p[i] - mean[i]);
                    for (row, di) in cov.iter_mut().zip(d).take(V::DIM) {
                        for (x, dj) in row.iter_mut().zip(d).take(V::DIM) {
                            *x += di * dj;
                        }
                    }
                }
            }
            Pass::Extremes { frame, lo, hi } => {
                for &p in chunk {
                    let local = frame.to_local(p);
                    (*lo, *hi) = (lo.min(local), hi.max(local));
                }
            }
            Pass::HalfExtents { obb, half } => {
                for &p in chunk {
                    *half = half.max(obb.to_local(p).abs());
                }
            }
            Pass::Contains(grown) => {
                if !chunk.iter().all(|&p| grown.contains(p)) {
                    self.pass = Pass::Done(unbounded());
                }
            }
            Pass::Done(_) => {}
        }
    }

    /// What follows the current pass, once it has read all `n` points.
    fn next_pass(&self, n: usize) -> Pass<V> {
        let count = n as f64;
        match self.pass {
            Pass::Mean(sum) => Pass::Covariance {
                mean: sum.map(|s| s / count),
                cov: [[0.0; 3]; 3],
            },
            Pass::Covariance { mean, cov } => {
                let axes = principal_frame::<V>(cov.map(|row| row.map(|x| x / count)));
                Pass::Extremes {
                    frame: Obb::new(V::from_dvec3(DVec3::from_array(mean)), axes, V::ZERO),
                    lo: V::INFINITY,
                    hi: V::NEG_INFINITY,
                }
            }
            Pass::Extremes { frame, lo, hi } => Pass::HalfExtents {
                // Halving before adding cannot overflow.
                obb: Obb::new(frame.to_world(lo * 0.5 + hi * 0.5), frame.axes, V::ZERO),
                half: V::ZERO,
            },
            Pass::HalfExtents { obb, half } => self.grown(Obb::new(obb.center, obb.axes, half)),
            Pass::Contains(obb) | Pass::Done(obb) => Pass::Done(obb),
        }
    }

    /// The PCA box grown by the node slack, or the unbounded box where rounding broke it.
    fn grown(&self, obb: Obb<V>) -> Pass<V> {
        if obb.is_empty() {
            return Pass::Done(obb);
        }
        let grow = growth(obb.center, magnitude(obb.half_extents));
        let grown = Obb::new(obb.center, obb.axes, obb.half_extents + V::splat(grow));
        let finite = grown.center.is_finite()
            && (0..V::DIM).all(|i| !grown.half_extents.coord(i).is_nan())
            && grown.axes.as_ref().iter().all(|a| a.is_finite());
        if !finite {
            Pass::Done(unbounded())
        } else if self.huge {
            Pass::Contains(grown)
        } else {
            Pass::Done(grown)
        }
    }
}

/// The box every test accepts.
fn unbounded<V: Vector>() -> Obb<V> {
    Obb::new(V::ZERO, V::identity_axes(), V::INFINITY)
}

/// The orthonormal frame of the covariance's eigenvectors, largest variance first, rounded
/// to `f32` and completed as [`Vector::principal_axes`] completes it.
fn principal_frame<V: Vector>(cov: [[f64; 3]; 3]) -> V::Axes {
    let frame: [Vec3; 3] = if V::DIM == 2 {
        let (_, vectors) = symmetric_eigen([[cov[0][0], cov[0][1]], [cov[1][0], cov[1][1]]]);
        let x = DVec2::from_array(vectors[0])
            .as_vec2()
            .try_normalize()
            .unwrap_or(Vec2::X);
        [x.extend(0.0), x.perp().extend(0.0), Vec3::Z]
    } else {
        let (_, vectors) = symmetric_eigen(cov);
        let first = DVec3::from_array(vectors[0]).as_vec3();
        let second = DVec3::from_array(vectors[1]).as_vec3();
        let x = first.try_normalize().unwrap_or(Vec3::X);
        let y = (second - x * x.dot(second))
            .try_normalize()
            .unwrap_or_else(|| x.any_orthonormal_vector());
        [x, y, x.cross(y)]
    };
    let mut axes = V::identity_axes();
    for (axis, v) in axes.as_mut().iter_mut().zip(frame) {
        *axis = V::from_dvec3(v.as_dvec3());
    }
    axes
}
