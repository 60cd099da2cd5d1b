//! Seeded scenes: random, and every degenerate case a builder or a traversal can trip on.

use bvhlab::Vector;
use rand_chacha::ChaCha8Rng;

use super::TestPrim;

/// `n` small random primitives in `[-10, 10]^DIM`.
pub fn random<P: TestPrim>(rng: &mut ChaCha8Rng, n: usize) -> Vec<P> {
    (0..n).map(|_| P::random(rng, 10.0)).collect()
}

/// The scenes every tree must handle, named: none, one, a few, random, duplicates (and one
/// primitive twenty times over), everything in one plane (a line in 2D), integer coordinates
/// (rays and split planes meet vertices exactly), everything on one line, clusters far
/// apart, and the random scene scaled by 1e-20 and 1e15 and moved to 1e6.
pub fn degenerate<P: TestPrim>(rng: &mut ChaCha8Rng) -> Vec<(&'static str, Vec<P>)> {
    let many: Vec<P> = random(rng, 300);
    let mut duplicates: Vec<P> = random(rng, 25);
    duplicates.extend(duplicates.clone());
    duplicates.extend(std::iter::repeat_n(duplicates[0], 20));
    let last = P::Point::DIM - 1;
    let flat = random::<P>(rng, 150)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                v.set_coord(last, 0.5);
                v
            })
        })
        .collect();
    let integer = random::<P>(rng, 150)
        .iter()
        .map(|p| {
            p.map(|mut v| {
                for i in 0..P::Point::DIM {
                    v.set_coord(i, v.coord(i).round());
                }
                v
            })
        })
        .collect();
    let line = random::<P>(rng, 100)
        .iter()
        .map(|p| {
            p.map(|v| {
                let mut w = P::Point::splat(0.0);
                w.set_coord(0, v.coord(0));
                w
            })
        })
        .collect();
    let clusters = random::<P>(rng, 120)
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let shift = P::Point::splat(if i % 2 == 0 { -1e4 } else { 1e4 });
            p.map(|v| v * 0.01 + shift)
        })
        .collect();
    let scaled = |s: f32| many.iter().map(|p| p.map(|v| v * s)).collect::<Vec<P>>();
    vec![
        ("empty", Vec::new()),
        ("one primitive", random(rng, 1)),
        ("a few", random(rng, 6)),
        ("random", many.clone()),
        ("duplicates", duplicates),
        ("all identical", vec![many[0]; 40]),
        ("flat", flat),
        ("integer coordinates", integer),
        ("on one line", line),
        ("two far clusters", clusters),
        ("tiny (x1e-20)", scaled(1e-20)),
        ("huge (x1e15)", scaled(1e15)),
        (
            "far from the origin",
            many.iter()
                .map(|p| p.map(|v| v + P::Point::splat(1e6)))
                .collect(),
        ),
    ]
}
