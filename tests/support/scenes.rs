//! Seeded scenes for the structure tests: random, degenerate and scaled, in 2D and 3D.

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::{Primitive, Segment2, Triangle3};
use rand_chacha::ChaCha8Rng;

use crate::random_vector;

/// A named scene.
pub struct Scene<P> {
    /// What it is, for failure messages.
    pub name: String,
    /// Its primitives.
    pub prims: Vec<P>,
}

fn scene<P>(name: impl Into<String>, prims: Vec<P>) -> Scene<P> {
    Scene {
        name: name.into(),
        prims,
    }
}

/// Short random segments in `[-10, 10]^2`.
pub fn random_segments(rng: &mut ChaCha8Rng, n: usize) -> Vec<Segment2> {
    (0..n)
        .map(|_| {
            let a: Vec2 = random_vector(rng, 10.0);
            Segment2::new(a, a + random_vector::<Vec2>(rng, 1.5))
        })
        .collect()
}

/// Small random triangles in `[-10, 10]^3`.
pub fn random_triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<Triangle3> {
    (0..n)
        .map(|_| {
            let a: Vec3 = random_vector(rng, 10.0);
            Triangle3::new(
                a,
                a + random_vector::<Vec3>(rng, 1.5),
                a + random_vector::<Vec3>(rng, 1.5),
            )
        })
        .collect()
}

fn scaled<P: Primitive + Map>(prims: &[P], s: f32) -> Vec<P> {
    prims.iter().map(|p| p.map(|v| v * s)).collect()
}

/// Applies a function to every vertex.
pub trait Map: Primitive {
    /// The primitive with every vertex mapped.
    #[must_use]
    fn map(&self, f: impl Fn(Self::Point) -> Self::Point) -> Self;
}

impl Map for Segment2 {
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        Segment2::new(f(self.a), f(self.b))
    }
}
impl Map for Triangle3 {
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        Triangle3::new(f(self.a), f(self.b), f(self.c))
    }
}
impl Map for Vec2 {
    fn map(&self, f: impl Fn(Vec2) -> Vec2) -> Self {
        f(*self)
    }
}
impl Map for Vec3 {
    fn map(&self, f: impl Fn(Vec3) -> Vec3) -> Self {
        f(*self)
    }
}

/// The standard set of scenes built from a generator of `n` random primitives: empty, one,
/// a few, many, duplicates, everything flattened onto one plane (line in 2D), a grid-aligned
/// scene with integer coordinates (so that rays meet split planes and cell boundaries exactly),
/// the same scene scaled by 1e-20 and 1e15 (squared distances of 1e20 overflow f32), and the
/// many with a NaN or infinite coordinate in some primitives (which no query may report).
pub fn standard_scenes<P: Map>(
    rng: &mut ChaCha8Rng,
    generate: impl Fn(&mut ChaCha8Rng, usize) -> Vec<P>,
) -> Vec<Scene<P>> {
    let many = generate(rng, 400);
    let one = generate(rng, 1);
    let mut duplicates = generate(rng, 30);
    let copies = duplicates.clone();
    duplicates.extend(copies.iter().copied());
    duplicates.extend(std::iter::repeat_n(copies[0], 20));
    let last = <P::Point as bvhlab::Vector>::DIM - 1;
    let flat: Vec<P> = generate(rng, 200)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                bvhlab::Vector::set_coord(&mut v, last, 0.5);
                v
            })
        })
        .collect();
    let integer: Vec<P> = generate(rng, 200)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                for i in 0..<P::Point as bvhlab::Vector>::DIM {
                    let c = bvhlab::Vector::coord(v, i);
                    bvhlab::Vector::set_coord(&mut v, i, c.round());
                }
                v
            })
        })
        .collect();
    vec![
        scene("empty", Vec::new()),
        scene("one primitive", one),
        scene("a few", generate(rng, 7)),
        scene("400 random", many.clone()),
        scene("duplicates", duplicates),
        scene("flat", flat),
        scene("integer grid coordinates", integer),
        scene("tiny (x1e-20)", scaled(&many, 1e-20)),
        scene("huge (x1e15)", scaled(&many, 1e15)),
        scene("with NaN and infinite coordinates", poisoned(&many)),
    ]
}

/// `prims` with one coordinate of one vertex of every 23rd primitive made NaN, `+inf` or
/// `-inf` in turn, on each axis in turn: segments and triangles that reach to infinity, and
/// points at infinity.
pub fn poisoned<P: Map>(prims: &[P]) -> Vec<P> {
    let dim = <P::Point as bvhlab::Vector>::DIM;
    prims
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if i % 23 != 0 {
                return *p;
            }
            let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][i / 23 % 3];
            let target = i / 23 % p.vertices().count();
            let vertex = std::cell::Cell::new(0);
            p.map(|mut v| {
                if vertex.replace(vertex.get() + 1) == target {
                    bvhlab::Vector::set_coord(&mut v, i / 23 % dim, bad);
                }
                v
            })
        })
        .collect()
}
