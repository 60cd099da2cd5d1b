//! Answering many queries at once: in the order that is kind to the caches, and on every core
//! with the `parallel` feature.
//!
//! Queries are independent and read-only, so neither the order they are answered in nor the
//! thread that answers them can change an answer: the batch calls answer exactly as one call
//! per query. Only the time differs.
//!
//! Points near each other in space visit the same nodes and primitives, so answering them one
//! after another finds those in the cache. A large batch of points is therefore answered in
//! Morton (Z-order) order of the points (Morton 1966; the usual way to sort queries or
//! primitives for locality, as in Lauterbach et al. 2009's LBVH), and the answers are put
//! back in the caller's order.

use crate::Vector;

/// Batches smaller than this are answered in the given order: sorting them costs more than
/// the cache saves.
const SORT_FROM: usize = 4096;

/// Bits of each coordinate in a Morton key (3 × 21 = 63 bits fit a `u64`).
const BITS_PER_AXIS: u32 = 21;

/// One answer per query, in order, on every core with the `parallel` feature.
pub(super) fn in_order<Q: Sync, A: Send>(
    queries: &[Q],
    answer: impl Fn(&Q) -> A + Sync + Send,
) -> Vec<A> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        queries.par_iter().map(answer).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        queries.iter().map(answer).collect()
    }
}

/// One answer per point, in the points' order, answered in Morton order of the points when
/// the batch is large enough to pay for the sort.
pub(super) fn by_location<V: Vector, A: Send>(
    points: &[V],
    answer: impl Fn(&V) -> A + Sync + Send,
) -> Vec<A> {
    if points.len() < SORT_FROM || u32::try_from(points.len()).is_err() {
        return in_order(points, answer);
    }
    let order = morton_order(points);
    let sorted = in_order(&order, |&i| answer(&points[i as usize]));
    // Put each answer back where its point was.
    let mut answers: Vec<Option<A>> = std::iter::repeat_with(|| None).take(points.len()).collect();
    for (&i, a) in order.iter().zip(sorted) {
        answers[i as usize] = Some(a);
    }
    answers
        .into_iter()
        .map(|a| a.unwrap_or_else(|| unreachable!("the order is a permutation of the points")))
        .collect()
}

/// The points' indices sorted by their Morton keys in the box of the finite points (ties, and
/// points with a NaN or infinite coordinate, which all get key 0, keep their order).
fn morton_order<V: Vector>(points: &[V]) -> Vec<u32> {
    let finite = |p: &V| (0..V::DIM).all(|axis| p.coord(axis).is_finite());
    let (lo, hi) = points.iter().filter(|p| finite(p)).fold(
        (V::splat(f32::INFINITY), V::splat(f32::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let cells = f64::from((1u32 << BITS_PER_AXIS) - 1);
    let key = |p: &V| -> u64 {
        if !finite(p) {
            return 0;
        }
        let mut key = 0u64;
        for axis in 0..V::DIM {
            let (l, h) = (f64::from(lo.coord(axis)), f64::from(hi.coord(axis)));
            let unit = if h > l {
                (f64::from(p.coord(axis)) - l) / (h - l)
            } else {
                0.0
            };
            #[expect(
                clippy::cast_possible_truncation,
                clippy::cast_sign_loss,
                reason = "unit is in [0, 1], so the cell is in [0, 2^21 - 1]"
            )]
            let cell = (unit.clamp(0.0, 1.0) * cells) as u64;
            key |= spread(cell, V::DIM) << axis;
        }
        key
    };
    let mut keyed: Vec<(u64, u32)> = points
        .iter()
        .zip(0u32..)
        .map(|(p, i)| (key(p), i))
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

/// The low [`BITS_PER_AXIS`] bits of `cell` spread `dim` places apart (bit `b` moves to bit
/// `b · dim`), so that the axes' bits interleave.
fn spread(cell: u64, dim: usize) -> u64 {
    (0..BITS_PER_AXIS).fold(0, |out, bit| {
        out | (((cell >> bit) & 1) << (bit as usize * dim))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    #[test]
    fn spread_interleaves_the_bits() {
        assert_eq!(spread(0b111, 3), 0b001_001_001);
        assert_eq!(spread(0b101, 2), 0b01_00_01);
    }

    #[test]
    fn morton_order_walks_the_quadrants_in_z_order_and_is_a_permutation() {
        // The four corners of a square, given in reverse Z order, and a NaN point.
        let points = [
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(f32::NAN, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
        ];
        assert_eq!(morton_order(&points), vec![2, 4, 3, 1, 0]);
    }

    #[test]
    fn answers_come_back_in_the_callers_order() {
        let points: Vec<Vec3> = (0..SORT_FROM as u32 * 2)
            .map(|i| {
                let f = i as f32;
                Vec3::new(
                    (f * 0.618).fract(),
                    (f * 0.414).fract(),
                    (f * 0.732).fract(),
                )
            })
            .collect();
        let answers = by_location(&points, |p| *p);
        assert_eq!(answers, points);
    }
}
