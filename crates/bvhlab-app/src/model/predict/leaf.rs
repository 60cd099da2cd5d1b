//! Questions at a primitive's test: does the ray hit it, does it become one of the nearest,
//! does it reach into the range.

use bvhlab::structure::PrimitiveResult;
use bvhlab::{Event, Vector};

use super::question::{About, At, Choice, PredictQuestion, shown_apart, yes_no};

/// Whether the ray hits a primitive; whether a primitive becomes one of the nearest; whether
/// it lies in the range.
pub(super) fn primitive<V: Vector>(
    at: &At<'_, V>,
    prim: u32,
    result: PrimitiveResult,
) -> Option<PredictQuestion> {
    let step = at.step();
    let next = at.next();
    let new_best = matches!(next, Some(Event::NewBest { prim: p, .. }) if p == prim);
    let reveal = 1 + usize::from(new_best);
    let (prompt, answer, why, hint) = match result {
        PrimitiveResult::Hit(t) => (
            format!("Does the ray hit primitive {prim}?"),
            Choice::Yes,
            format!("the ray hits primitive {prim} at t = {t:.3}"),
            "Follow the ray from its origin: does it cross the primitive before its end?",
        ),
        PrimitiveResult::Miss => (
            format!("Does the ray hit primitive {prim}?"),
            Choice::No,
            format!("the ray passes primitive {prim} by (or would meet it only beyond its end)"),
            "Follow the ray from its origin: does it cross the primitive before its end?",
        ),
        PrimitiveResult::Distance(d) => {
            let k = at.recording.question.k.max(1);
            let best = at.kth_best()?;
            // Both distances are shown, and must differ as shown.
            if !shown_apart(d, best) {
                return None;
            }
            let (answer, why) = if new_best {
                (
                    Choice::Yes,
                    format!(
                        "primitive {prim} is {d:.3} from the point, nearer than the best so far ({best:.3})"
                    ),
                )
            } else {
                (
                    Choice::No,
                    format!(
                        "primitive {prim} is {d:.3} from the point, no nearer than the best so far ({best:.3})"
                    ),
                )
            };
            let which = if k == 1 {
                "the nearest so far".to_owned()
            } else {
                format!("one of the {k} nearest so far")
            };
            return Some(PredictQuestion {
                step,
                prompt: format!("The best distance so far is {best:.3}; primitive {prim} is {d:.3} from the point. Does it become {which}?"),
                choices: yes_no(),
                answer,
                reveal,
                why,
                hint: "A primitive joins the best so far only when it is nearer than the best so far (the k-th best, for k nearest).".to_owned(),
                about: About::prim(prim),
            });
        }
        PrimitiveResult::Overlap => (
            format!("Does primitive {prim} reach into the range?"),
            Choice::Yes,
            format!("primitive {prim} overlaps the range"),
            "Does any part of the primitive lie inside the circle or box?",
        ),
        PrimitiveResult::NoOverlap => (
            format!("Does primitive {prim} reach into the range?"),
            Choice::No,
            format!("primitive {prim} lies wholly outside the range"),
            "Does any part of the primitive lie inside the circle or box?",
        ),
        PrimitiveResult::AlreadyTested => return None,
    };
    Some(PredictQuestion {
        step,
        prompt,
        choices: yes_no(),
        answer,
        reveal,
        why,
        hint: hint.to_owned(),
        about: About::prim(prim),
    })
}
