//! The baseline: test every primitive. The reference every structure is checked against, and
//! the counter the lab shows beside each structure's.
//!
//! "Every primitive" means every finite one: a primitive with a NaN or infinite coordinate is
//! never an answer ([`Primitive::has_finite_coordinates`]), here as in every structure, so brute force
//! skips it without a test (no event, no cost).

use super::query::{by_t_then_prim, placed};
use super::{
    Event, Hit, HitTracker, Nearest, NearestSet, Observer, PointOf, PrimitiveResult, QueryCost,
    RangeShape, SpatialIndex, Stats, Traced, ValidationError,
};
use crate::primitive::contract;
use crate::{Primitive, Ray, Vector};

/// No structure at all: every query tests every primitive (but those with a NaN or infinite
/// coordinate, which no query reports: [`Primitive::has_finite_coordinates`]).
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BruteForce<P: Primitive> {
    prims: Vec<P>,
}

fn prim_id(i: usize) -> u32 {
    i as u32
}

impl<P: Primitive> BruteForce<P> {
    /// The primitives a query tests, with their indices: the finite ones.
    fn finite(&self) -> impl Iterator<Item = (usize, &P)> {
        self.prims
            .iter()
            .enumerate()
            .filter(|(_, prim)| prim.has_finite_coordinates())
    }

    /// How many primitives a query tests.
    fn finite_count(&self) -> usize {
        self.finite().count()
    }
}

impl<P: Primitive> SpatialIndex for BruteForce<P> {
    type Prim = P;

    /// Keeps a copy of the primitives.
    fn build(prims: &[P]) -> Self {
        Self {
            prims: prims.to_vec(),
        }
    }

    fn primitives(&self) -> &[P] {
        &self.prims
    }

    fn ray_first_hit_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        let mut best = HitTracker::new(t_max);
        for (i, prim) in self.finite() {
            let t = contract::ray_hit(prim, ray).filter(|&t| t <= t_max);
            observer.on(Event::PrimitiveTest {
                prim: prim_id(i),
                result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
            });
            if let Some(t) = t
                && best.offer(i, t)
            {
                observer.on(Event::NewBest {
                    prim: prim_id(i),
                    value: t,
                });
            }
        }
        Traced {
            answer: placed(best.best(), &self.prims, ray),
            cost: tests(self.finite_count()),
        }
    }

    fn ray_any_hit_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Option<Hit>> {
        for (tested, (i, prim)) in self.finite().enumerate() {
            let t = contract::ray_hit(prim, ray).filter(|&t| t <= t_max);
            observer.on(Event::PrimitiveTest {
                prim: prim_id(i),
                result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
            });
            if let Some(t) = t {
                return Traced {
                    answer: Some(Hit::on(i, t, prim, ray)),
                    cost: tests(tested + 1),
                };
            }
        }
        Traced {
            answer: None,
            cost: tests(self.finite_count()),
        }
    }

    fn ray_all_hits_observed<O: Observer<P::Point>>(
        &self,
        ray: &Ray<P::Point>,
        t_max: f32,
        observer: &mut O,
    ) -> Traced<Vec<Hit>> {
        let mut hits: Vec<Hit> = Vec::new();
        for (i, prim) in self.finite() {
            let t = contract::ray_hit(prim, ray).filter(|&t| t <= t_max);
            observer.on(Event::PrimitiveTest {
                prim: prim_id(i),
                result: t.map_or(PrimitiveResult::Miss, PrimitiveResult::Hit),
            });
            hits.extend(t.map(|t| Hit::on(i, t, prim, ray)));
        }
        hits.sort_by(by_t_then_prim);
        Traced {
            answer: hits,
            cost: tests(self.finite_count()),
        }
    }

    fn k_nearest_observed<O: Observer<P::Point>>(
        &self,
        point: P::Point,
        k: usize,
        observer: &mut O,
    ) -> Traced<Vec<Nearest<P::Point>>> {
        if !point.is_finite() {
            return Traced {
                answer: Vec::new(),
                cost: QueryCost::default(),
            };
        }
        let mut nearest = NearestSet::new(k);
        for (i, prim) in self.finite() {
            let q = contract::project_point(prim, point);
            let d = (q - point).length();
            observer.on(Event::PrimitiveTest {
                prim: prim_id(i),
                result: PrimitiveResult::Distance(d),
            });
            if nearest.offer(i, q, d) {
                observer.on(Event::NewBest {
                    prim: prim_id(i),
                    value: d,
                });
            }
        }
        Traced {
            answer: nearest.into_vec(),
            cost: tests(self.finite_count()),
        }
    }

    fn range_observed<O: Observer<P::Point>>(
        &self,
        shape: &RangeShape<P::Point>,
        observer: &mut O,
    ) -> Traced<Vec<usize>> {
        let mut found = Vec::new();
        for (i, prim) in self.finite() {
            let overlap = shape.overlaps_primitive(prim);
            observer.on(Event::PrimitiveTest {
                prim: prim_id(i),
                result: if overlap {
                    PrimitiveResult::Overlap
                } else {
                    PrimitiveResult::NoOverlap
                },
            });
            if overlap {
                found.push(i);
            }
        }
        Traced {
            answer: found,
            cost: tests(self.finite_count()),
        }
    }

    fn collide_observed<O: Observer<PointOf<Self>>>(
        &self,
        other: &Self,
        observer: &mut O,
    ) -> Traced<Vec<(usize, usize)>> {
        let mut pairs = Vec::new();
        for (i, a) in self.finite() {
            for (j, b) in other.finite() {
                let overlap = a.intersects(b);
                observer.on(Event::PairTest {
                    a: prim_id(i),
                    b: prim_id(j),
                    overlap,
                });
                if overlap {
                    pairs.push((i, j));
                }
            }
        }
        Traced {
            answer: pairs,
            cost: tests(self.finite_count() * other.finite_count()),
        }
    }

    fn stats(&self) -> Stats {
        let n = self.prims.len();
        Stats {
            nodes: 1,
            leaves: 1,
            max_depth: 0,
            leaf_sizes: Stats::leaf_size_histogram(std::iter::once(n)),
            primitives: n,
            references: n,
            memory_bytes: n * size_of::<P>(),
            sah_cost: Some(n as f32),
        }
    }

    fn validate(&self) -> Result<(), ValidationError> {
        Ok(())
    }
}

fn tests(n: usize) -> QueryCost {
    QueryCost {
        nodes_visited: 0,
        bound_tests: 0,
        prim_tests: n as u64,
    }
}
