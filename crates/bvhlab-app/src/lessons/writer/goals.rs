//! The goals the writer offers: each quantity the lab knows a value for now, with that
//! value ("nodes visited: now 14") and the comparisons a teacher is likely to want from it
//! (`nodes-visited < 14`: "fewer than now"; `< compare` when two structures are shown;
//! `step = end`). Only goals that read are offered.

use crate::lessons::goal_text::{QUANTITIES, parse, value_text};
use crate::model::Lab;
use crate::model::goal::{Comparison, Goal, Quantity, Target, Value};

/// One quantity with its value now and the goals offered from it.
#[derive(Clone, Debug, PartialEq)]
pub struct Offer {
    /// The quantity's word in a goal (`nodes-visited`).
    pub quantity: &'static str,
    /// What it is, from the lessons' README.
    pub meaning: &'static str,
    /// Its value now, as a goal writes it (`14`, `hit`).
    pub now: String,
    /// Goals to add, each one that reads.
    pub goals: Vec<String>,
}

/// The quantities of the half shown that have a value now, each with its goals.
pub fn offers(lab: &Lab) -> Vec<Offer> {
    let compared = lab.dimension() == crate::model::Dimension::Two
        && lab.two().half.compare.is_some()
        || lab.dimension() == crate::model::Dimension::Three && lab.three().half.compare.is_some();
    QUANTITIES
        .iter()
        .filter_map(|&(word, quantity, meaning)| {
            let probe = Goal {
                quantity,
                comparison: Comparison::Equal,
                target: Target::Number(0.0),
                text: String::new(),
            };
            let value = probe.now(lab)?;
            let now = value_text(value);
            let mut goals = match value {
                Value::Word(_) => vec![format!("{word} = {now}"), format!("{word} != {now}")],
                Value::Number(_) if quantity == Quantity::Step => {
                    vec!["step = end".to_owned(), format!("step >= {now}")]
                }
                Value::Number(_) => vec![
                    format!("{word} < {now}"),
                    format!("{word} <= {now}"),
                    format!("{word} > {now}"),
                    format!("{word} >= {now}"),
                ],
            };
            if compared && matches!(value, Value::Number(_)) && quantity != Quantity::Step {
                goals.push(format!("{word} < compare"));
            }
            goals.retain(|g| parse(g).is_ok());
            (!goals.is_empty()).then_some(Offer {
                quantity: word,
                meaning,
                now,
                goals,
            })
        })
        .collect()
}
