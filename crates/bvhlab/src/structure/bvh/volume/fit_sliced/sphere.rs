//! The sphere-tree node fit ([`Sphere::ritter_fit`], then the growth and checks of
//! `volume/sphere.rs`) in four resumable passes over the node's vertices: the point farthest
//! from the first, the point farthest from that one (the two span the first sphere), the
//! pass that grows the sphere over each point left outside, and the radius measured as
//! `contains` measures it. A fifth pass checks containment for coordinates beyond [`HUGE`],
//! as the one-go fit does.
//!
//! Every fold is the one-go fit's, in the same order and precision, so the sphere is the same
//! to the bit. Ritter, "An Efficient Bounding Sphere", Graphics Gems, 1990.

use super::Cursor;
use crate::Vector;
use crate::structure::bvh::volume::{HUGE, growth, magnitude};
use crate::volume::sphere::round_up;
use crate::volume::{Aabb, BoundingVolume, Sphere};

/// Ritter's sphere of a node's vertices, a chunk of points at a time.
#[derive(Clone, Debug)]
pub(in crate::structure::bvh) struct RitterPasses<V: Vector> {
    /// Whether the node's coordinates exceed [`HUGE`], so that the sphere must be checked
    /// against every vertex.
    huge: bool,
    cursor: Cursor,
    pass: Pass<V>,
}

/// The farthest point seen so far and its squared distance.
type Farthest<V> = Option<(V, f32)>;

#[derive(Clone, Copy, Debug)]
enum Pass<V: Vector> {
    /// The point farthest from the first point.
    FromFirst(Farthest<V>),
    /// The point farthest from `y`, the answer of the first pass.
    FromY {
        y: V,
        farthest: Farthest<V>,
    },
    /// Growing the sphere over every point outside it.
    Grow(Sphere<V>),
    /// The largest distance from the centre, in `f64`.
    Enclose {
        probe: Sphere<V>,
        radius: f64,
    },
    /// Checking that the grown sphere holds every vertex (huge coordinates only).
    Contains(Sphere<V>),
    Done(Sphere<V>),
}

impl<V: Vector> RitterPasses<V> {
    /// The fit of a node with bounds `bounds`, before its first pass.
    pub fn new(bounds: &Aabb<V>) -> Self {
        Self {
            huge: magnitude(bounds.min).max(magnitude(bounds.max)) > HUGE,
            cursor: Cursor::default(),
            pass: Pass::FromFirst(None),
        }
    }

    /// The sphere, once every pass is done.
    pub fn result(&self) -> Option<Sphere<V>> {
        match self.pass {
            Pass::Done(sphere) => Some(sphere),
            _ => None,
        }
    }

    /// Reads about `units` points (at least one) or until the sphere is done; returns how
    /// many were read.
    pub fn advance(&mut self, points: &[V], units: usize) -> usize {
        let units = units.max(1);
        let mut read = 0;
        while read < units && self.result().is_none() {
            if self.cursor.at_end(points) {
                self.pass = self.next_pass();
                self.cursor = Cursor::default();
                continue;
            }
            let chunk = self.cursor.chunk(points, units - read);
            read += chunk.len();
            self.read(chunk, points[0]);
        }
        read
    }

    /// One chunk of the current pass; `first` is the first point.
    fn read(&mut self, chunk: &[V], first: V) {
        match &mut self.pass {
            Pass::FromFirst(farthest) => farthest_in(chunk, first, farthest),
            Pass::FromY { y, farthest } => farthest_in(chunk, *y, farthest),
            Pass::Grow(sphere) => {
                for &p in chunk {
                    let dist = (p - sphere.center).length();
                    if dist > sphere.radius {
                        // The new sphere touches p and the far side of the old one.
                        let radius = 0.5 * (sphere.radius + dist);
                        let center =
                            sphere.center + (p - sphere.center) * ((radius - sphere.radius) / dist);
                        *sphere = Sphere::new(center, radius);
                    }
                }
            }
            Pass::Enclose { probe, radius } => {
                for &p in chunk {
                    *radius = radius.max(probe.center_distance(p));
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

    /// What follows the current pass, once it has read every point.
    fn next_pass(&self) -> Pass<V> {
        match self.pass {
            Pass::FromFirst(farthest) => Pass::FromY {
                y: farthest.map_or(V::ZERO, |(p, _)| p),
                farthest: None,
            },
            Pass::FromY { y, farthest } => {
                let z = farthest.map_or(y, |(p, _)| p);
                Pass::Grow(Sphere::new((y + z) * 0.5, (z - y).length() * 0.5))
            }
            Pass::Grow(sphere) => Pass::Enclose {
                probe: Sphere::new(sphere.center, 0.0),
                radius: 0.0,
            },
            Pass::Enclose { probe, radius } => {
                self.grown(Sphere::new(probe.center, round_up(radius)))
            }
            Pass::Contains(sphere) | Pass::Done(sphere) => Pass::Done(sphere),
        }
    }

    /// Ritter's sphere grown by the node slack, or the unbounded sphere where rounding
    /// broke it.
    fn grown(&self, sphere: Sphere<V>) -> Pass<V> {
        if sphere.is_empty() {
            return Pass::Done(sphere);
        }
        let grown = Sphere::new(
            sphere.center,
            sphere.radius + growth(sphere.center, sphere.radius),
        );
        if !grown.center.is_finite() || grown.radius.is_nan() {
            Pass::Done(unbounded())
        } else if self.huge {
            Pass::Contains(grown)
        } else {
            Pass::Done(grown)
        }
    }
}

/// Folds `chunk` into the farthest point from `q`; of equally far points the last wins, as
/// with [`Iterator::max_by`].
fn farthest_in<V: Vector>(chunk: &[V], q: V, farthest: &mut Farthest<V>) {
    for &p in chunk {
        let d = (p - q).length_squared();
        if farthest.is_none_or(|(_, best)| d.total_cmp(&best).is_ge()) {
            *farthest = Some((p, d));
        }
    }
}

/// The sphere every test accepts.
fn unbounded<V: Vector>() -> Sphere<V> {
    Sphere::new(V::ZERO, f32::INFINITY)
}
