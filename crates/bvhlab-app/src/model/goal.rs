//! A lesson step's goal: a comparison read live from the lab ("primitives-tested < compare",
//! "answer = miss", "nodes-visited >= 90%"). A step's goal is reached when all its
//! comparisons hold at once; [`Lab`] checks after every action. The text form is parsed by
//! [`crate::lessons`], and its words are listed in `lessons/README.md`.

use bvhlab::Vector;
use bvhlab::volume::AxisSource;

use super::dimension::LabPrimitive;
use super::half::Half;
use super::question::{Task, Variant};
use super::recording::Answer;
use super::structures::StructureKind;
use super::{Dimension, Lab};

/// What a goal reads from the half shown (its first lane, unless compared with the second).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// Whether the query found something: `hit` or `miss` (for a point query, whether it
    /// found a primitive).
    Answer,
    /// The structure's kind.
    Structure,
    /// The task stepped through.
    Task,
    /// The algorithm's version.
    Variant,
    /// Nodes (cells) the whole query visited.
    NodesVisited,
    /// Bounding-volume (cell, plane) tests of the whole query.
    BoundTests,
    /// Primitive tests of the whole query.
    PrimitivesTested,
    /// The structure's nodes (cells).
    Nodes,
    /// The scene's primitives.
    Primitives,
    /// The playback step shown.
    Step,
    /// The ray direction's x, y or z component, as a unit vector.
    RayDirection(usize),
    /// How the BVH splits its nodes.
    Split,
    /// The structure's SAH cost.
    SahCost,
    /// Predict's questions answered right (first time or after a hint) in the exercise of
    /// the half shown.
    Predicted,
    /// How many of the separating-axis test's axes separate its two boxes (0: they
    /// overlap), in the half shown.
    SeparatingAxes,
    /// How many of the 3D test's nine edge-pair axes (`A_i × B_j`) separate its boxes.
    SeparatingEdgeAxes,
    /// How tightly a bounding volume fits the 2D selection or the 3D part: the convex hull's
    /// area (volume in 3D) over the volume's, in (0, 1].
    Tightness(bvhlab::FitKind),
    /// The ray origin's x, y or z.
    RayOrigin(usize),
}

/// How a quantity is compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// `=` (numbers: within a thousandth of the target's size, at least 0.001).
    Equal,
    /// `!=`.
    NotEqual,
    /// `<`.
    Less,
    /// `<=`.
    AtMost,
    /// `>`.
    Greater,
    /// `>=`.
    AtLeast,
}

/// A word a quantity can be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Word {
    /// The query found something.
    Hit,
    /// It found nothing.
    Miss,
    /// A structure.
    Structure(StructureKind),
    /// A task.
    Task(Task),
    /// A version of the algorithm.
    Variant(Variant),
    /// A BVH split method.
    Split(bvhlab::structure::SplitMethod),
}

/// What a quantity is compared with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// A number.
    Number(f64),
    /// A share of the structure's nodes (node quantities) or of the scene's primitives
    /// (primitive tests), in percent.
    Percent(f64),
    /// A word.
    Word(Word),
    /// The last playback step.
    End,
    /// The same quantity in the comparison's second lane.
    Compare,
}

/// One comparison of a goal.
#[derive(Clone, Debug, PartialEq)]
pub struct Goal {
    /// What is read.
    pub quantity: Quantity,
    /// How.
    pub comparison: Comparison,
    /// With what.
    pub target: Target,
    /// As the lesson wrote it (shown beside its mark).
    pub text: String,
}

/// A quantity's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    /// A count, a step or a coordinate.
    Number(f64),
    /// A word.
    Word(Word),
}

impl Goal {
    /// Whether the comparison holds in `lab` now (it does not while a value is unknown: no
    /// recording yet, no ray, no second lane).
    pub fn holds(&self, lab: &Lab) -> bool {
        if self.quantity.of_lab() {
            let (Some(value), Target::Number(n)) = (self.now(lab), self.target) else {
                return false;
            };
            return compare(value, self.comparison, Value::Number(n));
        }
        match lab.dimension() {
            Dimension::Two => self.holds_in(&lab.two().half, lab.two().prims().segments.len()),
            Dimension::Three => self.holds_in(&lab.three().half, lab.three().triangles().len()),
        }
    }

    /// The quantity's value now, or `None` while unknown.
    pub fn now(&self, lab: &Lab) -> Option<Value> {
        if self.quantity.of_lab() {
            return lab_value(lab, self.quantity);
        }
        match lab.dimension() {
            Dimension::Two => read(
                &lab.two().half,
                0,
                self.quantity,
                lab.two().prims().segments.len(),
            ),
            Dimension::Three => read(
                &lab.three().half,
                0,
                self.quantity,
                lab.three().triangles().len(),
            ),
        }
    }

    /// What the target stands for now (`None` while unknown): a percentage as a count, the
    /// last playback step, the second structure's value. A student reads it beside the
    /// value ("now 81 of 199 nodes, 41%"), so that a count is never shown against a share.
    pub fn target_now(&self, lab: &Lab) -> Option<Value> {
        if self.quantity.of_lab() {
            return match self.target {
                Target::Number(n) => Some(Value::Number(n)),
                _ => None,
            };
        }
        match lab.dimension() {
            Dimension::Two => self.target_in(&lab.two().half, lab.two().prims().segments.len()),
            Dimension::Three => self.target_in(&lab.three().half, lab.three().triangles().len()),
        }
    }

    /// The count a percentage is of now: the structure's nodes, or the scene's primitives
    /// for primitive counts (`None` while unknown, or when the target is no percentage).
    pub fn whole(&self, lab: &Lab) -> Option<f64> {
        if self.quantity.of_lab() || !matches!(self.target, Target::Percent(_)) {
            return None;
        }
        match lab.dimension() {
            Dimension::Two => self.whole_in(&lab.two().half, lab.two().prims().segments.len()),
            Dimension::Three => self.whole_in(&lab.three().half, lab.three().triangles().len()),
        }
    }

    fn whole_in<P: LabPrimitive>(&self, half: &Half<P>, primitives: usize) -> Option<f64> {
        match self.quantity {
            Quantity::PrimitivesTested | Quantity::Primitives => Some(primitives as f64),
            _ => match read(half, 0, Quantity::Nodes, primitives) {
                Some(Value::Number(n)) => Some(n),
                _ => None,
            },
        }
    }

    fn target_in<P: LabPrimitive>(&self, half: &Half<P>, primitives: usize) -> Option<Value> {
        Some(match self.target {
            Target::Number(n) => Value::Number(n),
            Target::Word(w) => Value::Word(w),
            Target::End => Value::Number(half.steps() as f64),
            Target::Percent(p) => Value::Number(p / 100.0 * self.whole_in(half, primitives)?),
            Target::Compare => read(half, 1, self.quantity, primitives)?,
        })
    }

    fn holds_in<P: LabPrimitive>(&self, half: &Half<P>, primitives: usize) -> bool {
        let (Some(value), Some(target)) = (
            read(half, 0, self.quantity, primitives),
            self.target_in(half, primitives),
        ) else {
            return false;
        };
        compare(value, self.comparison, target)
    }
}

impl Quantity {
    /// Whether it is read from the whole lab (Predict, the 2D half's volumes), not from the
    /// structures of the half shown.
    fn of_lab(self) -> bool {
        matches!(
            self,
            Self::Predicted | Self::SeparatingAxes | Self::SeparatingEdgeAxes | Self::Tightness(_)
        )
    }
}

/// A quantity read from the whole lab (see [`Quantity::of_lab`]).
fn lab_value(lab: &Lab, quantity: Quantity) -> Option<Value> {
    let two = Some(lab.two()).filter(|_| lab.dimension() == Dimension::Two);
    let three = Some(lab.three()).filter(|_| lab.dimension() == Dimension::Three);
    let separating_3d = |edges_only: bool| -> Option<f64> {
        let tests = three?.obb_pair?.tests();
        let separating = tests.iter().flatten().filter(|t| {
            t.separates() && (!edges_only || matches!(t.source, AxisSource::Edges(..)))
        });
        Some(separating.count() as f64)
    };
    let number = match quantity {
        Quantity::Predicted => {
            let score = lab.predict().score(&lab.exercise());
            f64::from(score.first_time + score.after_hint)
        }
        Quantity::SeparatingAxes if three.is_some() => separating_3d(false)?,
        Quantity::SeparatingAxes => {
            let pair = two?.obb_pair?;
            pair.tests().iter().filter(|t| t.separates()).count() as f64
        }
        Quantity::SeparatingEdgeAxes => separating_3d(true)?,
        Quantity::Tightness(kind) => {
            let report = match three {
                Some(three) => &three.part_fits()?.fits.as_ref()?.report,
                None => &two?.fits()?.report,
            };
            f64::from(report.get(kind)?.tightness?)
        }
        _ => return None,
    };
    Some(Value::Number(number))
}

/// `value` compared with `target`; words compare only for (in)equality.
fn compare(value: Value, comparison: Comparison, target: Value) -> bool {
    match (value, target) {
        (Value::Number(a), Value::Number(b)) => {
            let equal = (a - b).abs() <= (b.abs() * 1e-3).max(1e-3);
            match comparison {
                Comparison::Equal => equal,
                Comparison::NotEqual => !equal,
                Comparison::Less => a < b && !equal,
                Comparison::AtMost => a <= b || equal,
                Comparison::Greater => a > b && !equal,
                Comparison::AtLeast => a >= b || equal,
            }
        }
        (Value::Word(a), Value::Word(b)) => match comparison {
            Comparison::Equal => a == b,
            Comparison::NotEqual => a != b,
            _ => false,
        },
        _ => false,
    }
}

/// `quantity` in lane `lane` of `half` (`None`: unknown).
fn read<P: LabPrimitive>(
    half: &Half<P>,
    lane: usize,
    quantity: Quantity,
    primitives: usize,
) -> Option<Value> {
    if lane >= half.lane_count() {
        return None;
    }
    let lane = half.lane_at(lane);
    let number = |n: u64| Some(Value::Number(n as f64));
    // While a build runs, the recording and its marks are of the structure before it (a
    // mesh's old tree, another leaf size): an answer from there must not reach the goal of
    // a step that has just opened.
    let building = lane.job.is_some();
    let recording = lane.recorded().filter(|_| !building);
    match quantity {
        Quantity::Structure => Some(Value::Word(Word::Structure(lane.settings.kind))),
        Quantity::Task => Some(Value::Word(Word::Task(half.task))),
        Quantity::Variant => Some(Value::Word(Word::Variant(
            half.variant_for(lane.settings.kind),
        ))),
        Quantity::Primitives => number(primitives as u64),
        Quantity::Split => Some(Value::Word(Word::Split(lane.settings.bvh_split))),
        Quantity::SahCost => {
            let built = lane
                .structure
                .as_ref()
                .filter(|s| s.settings == lane.settings)?;
            let cost = built.stats.sah_cost?;
            Some(Value::Number(f64::from(cost)))
        }
        // Read from the lab, not a half (see `Goal::now`).
        Quantity::Predicted
        | Quantity::SeparatingAxes
        | Quantity::SeparatingEdgeAxes
        | Quantity::Tightness(_) => None,
        Quantity::Step => number(half.playback.shown(half.steps()) as u64),
        Quantity::Nodes => lane
            .marks()
            .filter(|_| !building)
            .map(|m| Value::Number(m.nodes.len() as f64)),
        Quantity::NodesVisited => number(recording?.cost.nodes_visited),
        Quantity::BoundTests => number(recording?.cost.bound_tests),
        Quantity::PrimitivesTested => number(recording?.cost.prim_tests),
        Quantity::Answer => {
            let found = match &recording?.answer {
                Answer::Hit(hit) => hit.is_some(),
                Answer::Hits(hits) => !hits.is_empty(),
                Answer::Nearest(nearest) => !nearest.is_empty(),
                Answer::Indices(indices) => !indices.is_empty(),
                Answer::Nodes(_) => return None,
            };
            Some(Value::Word(if found { Word::Hit } else { Word::Miss }))
        }
        Quantity::RayDirection(axis) | Quantity::RayOrigin(axis) => {
            let ray = recording?.question.ray?;
            if axis >= P::Point::DIM {
                return None;
            }
            let value = if matches!(quantity, Quantity::RayDirection(_)) {
                let dir = ray.dir();
                dir.coord(axis) / dir.length()
            } else {
                ray.origin().coord(axis)
            };
            Some(Value::Number(f64::from(value)))
        }
    }
}
