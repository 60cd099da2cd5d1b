//! A goal as a lesson writes it: `QUANTITY OP TARGET`, e.g. `answer = miss`,
//! `nodes-visited >= 90%`, `primitives-tested < compare`, `step = end`, `ray-dx = 0`.
//! [`QUANTITIES`] lists the quantities; a line that does not read is refused with what was
//! expected.

use bvhlab::FitKind;

use crate::model::goal::{Comparison, Goal, Quantity, Target, Word};
use crate::model::structures::StructureKind;
use crate::persist::{SplitName, StructureName, TaskName, VariantName};

/// The quantities a goal reads, with what each is (the lessons' README lists these).
pub const QUANTITIES: [(&str, Quantity, &str); 26] = [
    (
        "answer",
        Quantity::Answer,
        "hit or miss: whether the query found something",
    ),
    (
        "structure",
        Quantity::Structure,
        "the structure's name (kd-tree, grid, ...)",
    ),
    (
        "task",
        Quantity::Task,
        "the task's name (first-hit, nearest, build, ...)",
    ),
    (
        "variant",
        Quantity::Variant,
        "full, lecture or lecture-pruned",
    ),
    (
        "nodes-visited",
        Quantity::NodesVisited,
        "nodes (cells) the query visited",
    ),
    (
        "bound-tests",
        Quantity::BoundTests,
        "bounding-volume (cell, plane) tests of the query",
    ),
    (
        "primitives-tested",
        Quantity::PrimitivesTested,
        "primitive tests of the query",
    ),
    ("nodes", Quantity::Nodes, "the structure's nodes (cells)"),
    ("primitives", Quantity::Primitives, "the scene's primitives"),
    (
        "step",
        Quantity::Step,
        "the playback step shown (end: the last)",
    ),
    (
        "ray-dx",
        Quantity::RayDirection(0),
        "the ray direction's x, as a unit vector",
    ),
    (
        "ray-dy",
        Quantity::RayDirection(1),
        "the ray direction's y, as a unit vector",
    ),
    (
        "ray-dz",
        Quantity::RayDirection(2),
        "the ray direction's z, as a unit vector (3D)",
    ),
    (
        "split",
        Quantity::Split,
        "how the BVH splits its nodes (spatial-median, object-median, binned-sah)",
    ),
    (
        "sah-cost",
        Quantity::SahCost,
        "the structure's SAH cost (the expected cost of a random ray, in box tests)",
    ),
    (
        "predicted",
        Quantity::Predicted,
        "Predict's questions answered right (first time or after a hint) in this exercise",
    ),
    (
        "separating-axes",
        Quantity::SeparatingAxes,
        "how many axes separate the two boxes of the separating-axis test (0: they overlap)",
    ),
    (
        "separating-edge-axes",
        Quantity::SeparatingEdgeAxes,
        "how many of the 3D test's nine edge-pair axes (A_i × B_j) separate its boxes",
    ),
    (
        "tightness-sphere",
        Quantity::Tightness(FitKind::SphereCentroid),
        "the convex hull's area (3D: volume) over the centroid sphere's, 0 to 1, for the 2D selection or the 3D part",
    ),
    (
        "tightness-ritter",
        Quantity::Tightness(FitKind::SphereRitter),
        "the hull's area (3D: volume) over Ritter's sphere's",
    ),
    (
        "tightness-welzl",
        Quantity::Tightness(FitKind::SphereWelzl),
        "the hull's area (3D: volume) over Welzl's minimal sphere's",
    ),
    (
        "tightness-aabb",
        Quantity::Tightness(FitKind::Aabb),
        "the hull's area (3D: volume) over the AABB's",
    ),
    (
        "tightness-obb",
        Quantity::Tightness(FitKind::Obb),
        "the hull's area (3D: volume) over the PCA OBB's",
    ),
    ("ray-x", Quantity::RayOrigin(0), "the ray origin's x"),
    ("ray-y", Quantity::RayOrigin(1), "the ray origin's y"),
    ("ray-z", Quantity::RayOrigin(2), "the ray origin's z (3D)"),
];

/// The comparisons, longest first (so `<=` is not read as `<`).
const COMPARISONS: [(&str, Comparison); 7] = [
    ("<=", Comparison::AtMost),
    (">=", Comparison::AtLeast),
    ("!=", Comparison::NotEqual),
    ("==", Comparison::Equal),
    ("=", Comparison::Equal),
    ("<", Comparison::Less),
    (">", Comparison::Greater),
];

/// Reads one goal.
///
/// # Errors
/// What does not read, and what was expected there.
pub fn parse(text: &str) -> Result<Goal, String> {
    let (at, symbol, comparison) = COMPARISONS
        .iter()
        .filter_map(|&(symbol, c)| text.find(symbol).map(|at| (at, symbol, c)))
        // The first comparison in the line; at one place, the longest (listed first).
        .min_by_key(|&(at, _, _)| at)
        .ok_or_else(|| format!("the goal \"{text}\" has no comparison (=, !=, <, <=, >, >=)"))?;
    let name = text[..at].trim();
    let value = text[at + symbol.len()..].trim();
    let quantity = QUANTITIES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|&(_, q, _)| q)
        .ok_or_else(|| {
            let names: Vec<&str> = QUANTITIES.iter().map(|(n, _, _)| *n).collect();
            format!(
                "the goal \"{text}\": {}",
                crate::persist::no_such_name("quantity", name, &names)
            )
        })?;
    let target = target(quantity, value).map_err(|e| format!("the goal \"{text}\": {e}"))?;
    let words = matches!(target, Target::Word(_));
    if words && !matches!(comparison, Comparison::Equal | Comparison::NotEqual) {
        return Err(format!(
            "the goal \"{text}\": a name is compared with = or != only"
        ));
    }
    Ok(Goal {
        quantity,
        comparison,
        target,
        text: text.trim().to_owned(),
    })
}

/// What `quantity` is compared with, read from `value`.
fn target(quantity: Quantity, value: &str) -> Result<Target, String> {
    let word = |names: &[&str], kind: &str| crate::persist::no_such_name(kind, value, names);
    match quantity {
        Quantity::Answer => match value {
            "hit" => Ok(Target::Word(Word::Hit)),
            "miss" => Ok(Target::Word(Word::Miss)),
            _ => Err(word(&["hit", "miss"], "answer")),
        },
        Quantity::Structure => StructureName::from_name(value)
            .map(|s| Target::Word(Word::Structure(s.into())))
            .ok_or_else(|| word(StructureName::NAMES, "structure")),
        Quantity::Task => TaskName::from_name(value)
            .map(|t| Target::Word(Word::Task(t.into())))
            .ok_or_else(|| word(TaskName::NAMES, "task")),
        Quantity::Split => SplitName::from_name(value)
            .map(|v| Target::Word(Word::Split(v.into())))
            .ok_or_else(|| word(SplitName::NAMES, "split")),
        Quantity::Variant => VariantName::from_name(value)
            .map(|v| Target::Word(Word::Variant(v.into())))
            .ok_or_else(|| word(VariantName::NAMES, "variant")),
        _ if value == "compare" => Ok(Target::Compare),
        Quantity::Step if value == "end" => Ok(Target::End),
        _ => {
            let (digits, percent) = match value.strip_suffix('%') {
                Some(d) => (d.trim(), true),
                None => (value, false),
            };
            let n: f64 = digits
                .parse()
                .ok()
                .filter(|n: &f64| n.is_finite())
                .ok_or_else(|| {
                    format!(
                        "\"{value}\" is not a number (nor compare{})",
                        if quantity == Quantity::Step {
                            ", nor end"
                        } else {
                            ""
                        }
                    )
                })?;
            if !percent {
                return Ok(Target::Number(n));
            }
            let counts = matches!(
                quantity,
                Quantity::NodesVisited
                    | Quantity::BoundTests
                    | Quantity::PrimitivesTested
                    | Quantity::Nodes
                    | Quantity::Primitives
            );
            if counts {
                Ok(Target::Percent(n))
            } else {
                Err(
                    "a percentage is of the nodes or the primitives: only their counts take one"
                        .to_owned(),
                )
            }
        }
    }
}

/// A goal's value as a lesson writes it: `37`, `0.707`, `hit`, `aabb-tree`.
pub fn value_text(value: crate::model::goal::Value) -> String {
    use crate::model::goal::Value;
    let stored = |name: Result<serde_json::Value, serde_json::Error>| match name {
        Ok(serde_json::Value::String(word)) => word,
        _ => String::from("?"),
    };
    match value {
        Value::Number(n) if n.fract() == 0.0 => format!("{n}"),
        Value::Number(n) => format!("{n:.3}"),
        Value::Word(Word::Hit) => "hit".to_owned(),
        Value::Word(Word::Miss) => "miss".to_owned(),
        Value::Word(Word::Structure(s)) => stored(serde_json::to_value(StructureName::from(s))),
        Value::Word(Word::Task(t)) => stored(serde_json::to_value(TaskName::from(t))),
        Value::Word(Word::Variant(v)) => stored(serde_json::to_value(VariantName::from(v))),
        Value::Word(Word::Split(v)) => stored(serde_json::to_value(SplitName::from(v))),
    }
}

/// A goal's value now as the lesson panel shows it beside the goal, with what its target
/// stands for now where the goal's text does not say it: `now 81 of 199 nodes, 41%`,
/// `now 12, the second structure 15`, `now step 3 of 40`, or `unknown yet`.
pub fn now_text(goal: &Goal, lab: &crate::model::Lab) -> String {
    use crate::model::goal::Value;
    let Some(value) = goal.now(lab) else {
        return "unknown yet".to_owned();
    };
    let now = match value {
        // The 3D half names its quadtree as the lab does there.
        Value::Word(Word::Structure(StructureKind::Quadtree))
            if lab.dimension() == crate::model::Dimension::Three =>
        {
            StructureKind::Quadtree.label_in(3).to_owned()
        }
        _ => value_text(value),
    };
    match (goal.target, value, goal.target_now(lab)) {
        (Target::Percent(_), Value::Number(n), _) => match goal.whole(lab) {
            Some(whole) if whole > 0.0 => {
                let of = match goal.quantity {
                    Quantity::PrimitivesTested | Quantity::Primitives => "primitives",
                    _ => "nodes",
                };
                format!("now {now} of {whole} {of}, {:.0}%", 100.0 * n / whole)
            }
            _ => format!("now {now}"),
        },
        (Target::Compare, _, Some(other)) => {
            format!("now {now}, the second structure {}", value_text(other))
        }
        (Target::End, _, Some(end)) => format!("now step {now} of {}", value_text(end)),
        _ => format!("now {now}"),
    }
}
