//! The question of a grid's ray walk: which cell the ray enters next.

use bvhlab::Vector;

use super::question::{AXES, About, At, Choice, PredictQuestion};

/// Which cell a grid's ray walk enters next: a neighbour across one face.
pub(super) fn next_cell<V: Vector>(at: &At<'_, V>, coords: [u32; 3]) -> Option<PredictQuestion> {
    let last = at.snapshot.cells.last()?;
    let dir = at.recording.question.ray?.dir();
    let moved: Vec<(usize, bool)> = (0..V::DIM)
        .filter(|&a| coords[a] != last.coords[a])
        .map(|a| (a, coords[a] > last.coords[a]))
        .collect();
    let [(axis, up)] = moved[..] else {
        return None;
    };
    if coords[axis].abs_diff(last.coords[axis]) != 1 {
        return None;
    }
    let choices: Vec<(Choice, String)> = (0..V::DIM)
        .filter(|&a| dir.coord(a) != 0.0)
        .map(|a| {
            let up = dir.coord(a) > 0.0;
            let sign = if up { "+" } else { "-" };
            (
                Choice::Cell { axis: a as u8, up },
                format!("the next cell along {sign}{}", AXES[a]),
            )
        })
        .collect();
    if choices.len() < 2 {
        return None;
    }
    let here = coords_text(last.coords, V::DIM);
    Some(PredictQuestion {
        step: at.step(),
        prompt: format!("The ray is in cell {here} until t = {:.3}. Which cell does it enter next?", last.t_exit),
        choices,
        answer: Choice::Cell { axis: axis as u8, up },
        reveal: 1,
        why: format!(
            "at t = {:.3} the ray reaches the cell's {} side before any other: it crosses into cell {}",
            last.t_exit,
            AXES[axis],
            coords_text(coords, V::DIM)
        ),
        hint: "The ray leaves a cell through the side it reaches first: compare the t of the next vertical and the next horizontal grid line.".to_owned(),
        about: About::nodes([last.cell]),
    })
}

fn coords_text(coords: [u32; 3], dim: usize) -> String {
    let c: Vec<String> = coords[..dim].iter().map(u32::to_string).collect();
    format!("({})", c.join(", "))
}
