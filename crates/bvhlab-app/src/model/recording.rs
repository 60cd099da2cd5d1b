//! One query or build, recorded for playback: every event the core reported, its answer and
//! cost, and brute force's answer and cost for the same question.
//!
//! A recording is made once per question (task, variant, ray or point, scene, settings) and
//! replayed by [`super::playback`]; dragging the ray re-records it.

use bvhlab::glam::Vec2;
use bvhlab::structure::RangeShape;
use bvhlab::structure::bvh::{NodeVolume, SplitRecord};
use bvhlab::{
    Aabb, BruteForce, Event, Hit, Nearest, Obb, Primitive, QueryCost, Ray, Recorder, SpatialIndex,
    Sphere, Traced, Vector,
};

pub use super::question::Question;
use super::question::{Task, Variant};
use super::structures::{BuildSettings, Built};

/// What a question is asked of: a built structure, brute force over the same primitives, and
/// what the recording remembers about where they came from.
#[derive(Clone, Copy)]
pub struct Subject<'a, P: Primitive> {
    /// The structure.
    pub structure: &'a Built<P>,
    /// The baseline over the same primitives.
    pub brute: &'a BruteForce<P>,
    /// The primitives (a build is recorded by building again, observed).
    pub prims: &'a [P],
    /// The settings the structure was built with.
    pub settings: BuildSettings,
    /// The scene revision it was built on.
    pub revision: u64,
    /// Its node count.
    pub node_count: usize,
}

/// A query's or build's answer, in a form the panels can print and compare.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer<V: Vector = Vec2> {
    /// First or any hit.
    Hit(Option<Hit>),
    /// All hits, nearest first.
    Hits(Vec<Hit>),
    /// The k nearest, nearest first.
    Nearest(Vec<Nearest<V>>),
    /// The primitives in the range, ascending.
    Indices(Vec<usize>),
    /// A build: how many nodes it made.
    Nodes(usize),
}

/// A recorded query or build.
#[derive(Clone, Debug)]
pub struct Recording<V: Vector = Vec2> {
    /// The question it answers.
    pub question: Question<V>,
    /// The scene revision and settings it was recorded on.
    pub on: (u64, BuildSettings),
    /// Every event, in order.
    pub events: Vec<Event<V>>,
    /// The structure's answer.
    pub answer: Answer<V>,
    /// What the structure's answer cost (the core's own count).
    pub cost: QueryCost,
    /// Brute force's answer (none for builds).
    pub brute_answer: Option<Answer<V>>,
    /// What brute force cost.
    pub brute_cost: QueryCost,
    /// A BVH build's split decisions, with their SAH cost curves.
    pub splits: Vec<SplitRecord>,
    /// Every variant of the algorithm that exists here, with its total cost, so the panel
    /// can show what the slides' version costs beside the full one.
    pub variant_costs: Vec<(Variant, QueryCost)>,
}

impl<V: Vector> Recording<V>
where
    Sphere<V>: NodeVolume<Point = V>,
    Aabb<V>: NodeVolume<Point = V>,
    Obb<V>: NodeVolume<Point = V>,
{
    /// Records `question` on `built`.
    ///
    /// # Errors
    /// Why the question cannot be asked: no ray or point yet, or a variant that does not
    /// exist for this structure.
    pub fn record_on<P: Primitive<Point = V>>(
        built: Subject<'_, P>,
        question: Question<V>,
    ) -> Result<Self, String> {
        let on = (built.revision, built.settings);
        if question.task == Task::Build {
            let mut recorder = Recorder::default();
            let (_, splits) =
                Built::build_observed(built.prims, &built.settings, &mut recorder, true);
            return Ok(Self {
                question,
                on,
                events: recorder.events,
                answer: Answer::Nodes(built.node_count),
                cost: QueryCost::default(),
                brute_answer: None,
                brute_cost: QueryCost::default(),
                splits,
                variant_costs: Vec::new(),
            });
        }
        let mut recorder = Recorder::default();
        let traced = ask(&built, &question, question.variant, &mut recorder)?;
        let brute = ask_brute(&built, &question)?;
        let variant_costs = crate::pseudocode::variants(built.settings.kind, question.task)
            .into_iter()
            .filter_map(|v| {
                let cost = if v == question.variant {
                    traced.cost
                } else {
                    ask(&built, &question, v, &mut ()).ok()?.cost
                };
                Some((v, cost))
            })
            .collect();
        Ok(Self {
            question,
            on,
            events: recorder.events,
            answer: traced.answer,
            cost: traced.cost,
            brute_answer: Some(brute.answer),
            brute_cost: brute.cost,
            splits: Vec::new(),
            variant_costs,
        })
    }

    /// The live ray answer, when this recording is the full first-hit query (so a drag
    /// runs the query once, not once for the panel and once for playback).
    pub fn ray_outcome(&self) -> Option<super::outcome::RayOutcome<V>> {
        let q = &self.question;
        match (&self.answer, &self.brute_answer, q.ray) {
            (Answer::Hit(hit), Some(Answer::Hit(brute)), Some(ray))
                if q.task == Task::FirstHit && q.variant == Variant::Full =>
            {
                Some(super::outcome::RayOutcome {
                    ray,
                    hit: *hit,
                    cost: self.cost,
                    brute_hit: *brute,
                    brute_cost: self.brute_cost,
                    events: self.events.clone(),
                })
            }
            _ => None,
        }
    }

    /// The live point answer, when this recording is the full k-nearest query.
    pub fn point_outcome(&self) -> Option<super::outcome::PointOutcome<V>> {
        let q = &self.question;
        match (&self.answer, &self.brute_answer, q.point) {
            (Answer::Nearest(nearest), Some(Answer::Nearest(brute)), Some(point))
                if q.task == Task::Nearest && q.variant == Variant::Full =>
            {
                Some(super::outcome::PointOutcome {
                    point,
                    k: q.k.max(1),
                    nearest: nearest.clone(),
                    cost: self.cost,
                    brute_nearest: brute.clone(),
                    brute_cost: self.brute_cost,
                    events: self.events.clone(),
                })
            }
            _ => None,
        }
    }

    /// Whether the structure's answer is brute force's (builds always agree). An any-hit
    /// query may find any hit: it agrees when both find one or neither does.
    pub fn agrees(&self) -> bool {
        match (&self.answer, &self.brute_answer) {
            (_, None) => true,
            (Answer::Hit(a), Some(Answer::Hit(b))) if self.question.task == Task::AnyHit => {
                a.is_some() == b.is_some()
            }
            (a, Some(b)) => a == b,
        }
    }
}

/// The ray and point of a question, or why they are missing.
fn inputs<V: Vector>(question: &Question<V>) -> Result<(Option<Ray<V>>, Option<V>), String> {
    let in_3d = V::DIM == 3;
    match question.task {
        Task::FirstHit | Task::AnyHit | Task::AllHits => {
            question.ray.map(|r| (Some(r), None)).ok_or_else(|| {
                if in_3d {
                    "Cast a ray first (click the mesh, or set its origin and direction)."
                } else {
                    "Draw a ray first (Ray tool: drag on the canvas)."
                }
                .to_owned()
            })
        }
        Task::Nearest | Task::Range => question.point.map(|p| (None, Some(p))).ok_or_else(|| {
            if in_3d {
                "Place a query point first (Point tool: click the mesh, or type it in)."
            } else {
                "Place a query point first (Point tool: click the canvas)."
            }
            .to_owned()
        }),
        Task::Build => Ok((None, None)),
    }
}

/// The range query's shape: a disc of `radius` around the point.
fn disc<V: Vector>(point: V, radius: f32) -> Result<RangeShape<V>, String> {
    if radius.is_finite() && radius >= 0.0 {
        Ok(RangeShape::Ball(Sphere::new(point, radius)))
    } else {
        Err(format!("The range radius {radius} is not a finite length."))
    }
}

/// Asks the structure, with the variant's algorithm.
fn ask<P, O>(
    built: &Subject<'_, P>,
    question: &Question<P::Point>,
    variant: Variant,
    observer: &mut O,
) -> Result<Traced<Answer<P::Point>>, String>
where
    P: Primitive,
    O: bvhlab::Observer<P::Point>,
    Sphere<P::Point>: NodeVolume<Point = P::Point>,
    Aabb<P::Point>: NodeVolume<Point = P::Point>,
    Obb<P::Point>: NodeVolume<Point = P::Point>,
{
    let (ray, point) = inputs(question)?;
    let s = built.structure;
    let wrap = |t: Traced<Answer<P::Point>>| Ok(t);
    match (question.task, variant, ray, point) {
        (Task::FirstHit, Variant::Full, Some(r), _) => {
            wrap(map(s.ray_first_hit(&r, observer), Answer::Hit))
        }
        (Task::FirstHit, Variant::Lecture, Some(r), _) => s
            .lecture_intersect(&r, observer)
            .map(|t| map(t, Answer::Hit))
            .ok_or_else(|| not_offered(built, question.task, variant)),
        (Task::AnyHit, Variant::Full, Some(r), _) => {
            wrap(map(s.ray_any_hit(&r, observer), Answer::Hit))
        }
        (Task::AllHits, Variant::Full, Some(r), _) => {
            wrap(map(s.ray_all_hits(&r, observer), Answer::Hits))
        }
        (Task::Nearest, Variant::Full, _, Some(p)) => wrap(map(
            s.k_nearest(p, question.k.max(1), observer),
            Answer::Nearest,
        )),
        (Task::Nearest, Variant::Lecture | Variant::LecturePruned, _, Some(p)) => s
            .lecture_min_distance(p, variant == Variant::LecturePruned, observer)
            .map(|t| map(t, |n| Answer::Nearest(n.into_iter().collect())))
            .ok_or_else(|| not_offered(built, question.task, variant)),
        (Task::Range, Variant::Full, _, Some(p)) => {
            let shape = disc(p, question.radius)?;
            wrap(map(s.range(&shape, observer), Answer::Indices))
        }
        _ => Err(not_offered(built, question.task, variant)),
    }
}

fn not_offered<P: Primitive>(built: &Subject<'_, P>, task: Task, variant: Variant) -> String {
    format!(
        "The {variant:?} version of {task:?} exists only for BVHs, not for the {}.",
        built.settings.kind.label_in(P::Point::DIM)
    )
}

fn map<T, V: Vector>(traced: Traced<T>, f: impl FnOnce(T) -> Answer<V>) -> Traced<Answer<V>> {
    Traced {
        answer: f(traced.answer),
        cost: traced.cost,
    }
}

/// Asks brute force the same question. The lecture's nearest variants find one primitive,
/// so brute force is asked for one too.
fn ask_brute<P: Primitive>(
    built: &Subject<'_, P>,
    question: &Question<P::Point>,
) -> Result<Traced<Answer<P::Point>>, String> {
    let (ray, point) = inputs(question)?;
    let b = built.brute;
    let k = if question.variant == Variant::Full {
        question.k.max(1)
    } else {
        1
    };
    Ok(match (question.task, ray, point) {
        (Task::FirstHit, Some(r), _) => map(
            b.ray_first_hit_observed(&r, f32::INFINITY, &mut ()),
            Answer::Hit,
        ),
        (Task::AnyHit, Some(r), _) => map(
            b.ray_any_hit_observed(&r, f32::INFINITY, &mut ()),
            Answer::Hit,
        ),
        (Task::AllHits, Some(r), _) => map(
            b.ray_all_hits_observed(&r, f32::INFINITY, &mut ()),
            Answer::Hits,
        ),
        (Task::Nearest, _, Some(p)) => map(b.k_nearest_observed(p, k, &mut ()), Answer::Nearest),
        (Task::Range, _, Some(p)) => map(
            b.range_observed(&disc(p, question.radius)?, &mut ()),
            Answer::Indices,
        ),
        _ => return Err("Nothing to compare.".to_owned()),
    })
}
