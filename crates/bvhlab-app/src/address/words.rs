//! The other way round from [`super::StartParams`]: what the lab shows now, in the address's
//! words (`preset=kd-tree&structure=kd-tree&task=first-hit&ray=0,4.5,1,0`). The lesson
//! writer makes a step's setup and solution with it, and says what the words cannot hold
//! (a scene drawn by hand, a mesh from a file, a leaf size), so a teacher knows what a
//! student will not see.

use crate::model::{Dimension, Lab};
use crate::persist::{Coord, SavedState, SettingsState};

/// The half shown, in the address's words, and what the words leave out.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Described {
    /// `name=value` pairs joined by `&`.
    pub words: String,
    /// What is on screen that the words cannot say, one sentence each.
    pub unsaid: Vec<String>,
}

/// What `lab`'s half shown is, in the address's words.
pub fn describe(lab: &Lab) -> Described {
    let state = SavedState::capture(lab);
    let mut words = Vec::new();
    let mut unsaid = Vec::new();
    let (structure, compare, task, variant, step) = if lab.dimension() == Dimension::Three {
        let three = state.three.clone().unwrap_or_default();
        match &three.mesh {
            crate::persist::MeshState::Builtin(slug) => words.push(format!("mesh={slug}")),
            crate::persist::MeshState::File(name) => unsaid.push(format!(
                "the mesh {name} is a file: a step can open only a built-in mesh"
            )),
        }
        if let Some(ray) = &three.ray {
            let numbers = [ray.origin, ray.direction].concat();
            words.push(format!("ray={}", numbers_text(&numbers)));
        }
        if let Some(point) = &three.point {
            words.push(format!("point={}", numbers_text(point)));
        }
        let lab3d = lab.three();
        if lab3d.volumes.shown {
            words.push(format!("volumes={}", lab3d.volumes.part.word()));
        }
        if let Some(pair) = &three.obb_pair {
            let numbers = [pair.a, pair.b].map(|b| [b.center, b.half, b.degrees].concat());
            words.push(format!("obbs={}", numbers_text(&numbers.concat())));
        }
        (
            three.structure,
            three.compare,
            three.task,
            three.variant,
            three.playback.unwrap_or_default(),
        )
    } else {
        words.push(format!("preset={}", name(&state.preset)));
        if matches!(state.scene, crate::persist::SceneState::Shapes(_)) {
            unsaid.push(format!(
                "the scene was changed by hand: a step starts with the preset's shapes ({})",
                name(&state.preset)
            ));
        }
        if let Some(ray) = &state.ray {
            let direction = [
                Coord(ray.target[0].0 - ray.origin[0].0),
                Coord(ray.target[1].0 - ray.origin[1].0),
            ];
            let numbers = [ray.origin, direction].concat();
            words.push(format!("ray={}", numbers_text(&numbers)));
        }
        if let Some(point) = &state.point {
            words.push(format!("point={}", numbers_text(point)));
        }
        (
            state.structure,
            state.compare,
            Some(state.task),
            Some(state.variant),
            state.playback,
        )
    };
    words.push(format!("structure={}", name(&structure.kind)));
    if let Some(compare) = compare {
        words.push(format!("compare={}", name(&compare.kind)));
    }
    let kind: crate::model::structures::StructureKind = structure.kind.into();
    if kind.is_bvh() && structure.bvh_split != SettingsState::default().bvh_split {
        words.push(format!("split={}", name(&structure.bvh_split)));
    }
    unsaid.extend(settings_unsaid(&structure));
    // Said always: a ray or a point alone would pick its own task.
    if let Some(task) = task {
        words.push(format!("task={}", name(&task)));
    }
    if let Some(variant) = variant.map(|v| name(&v)).filter(|v| v != "full") {
        words.push(format!("variant={variant}"));
    }
    if !step.live {
        words.push(format!("step={}", step.step));
    }
    Described {
        words: words.join("&"),
        unsaid,
    }
}

/// The pairs of `now` that `setup` does not already say (the same name with the same value):
/// a solution is put in place on top of its step's setup, so it need only say what changes.
pub fn words_added(setup: &str, now: &str) -> String {
    let said: Vec<&str> = setup.split('&').collect();
    now.split('&')
        .filter(|pair| !pair.is_empty() && !said.contains(pair))
        .collect::<Vec<_>>()
        .join("&")
}

/// The build settings other than the structure and split that differ from the defaults: the
/// address has no words for them.
fn settings_unsaid(settings: &SettingsState) -> Vec<String> {
    let default = SettingsState {
        kind: settings.kind,
        bvh_split: settings.bvh_split,
        ..SettingsState::default()
    };
    if *settings == default {
        Vec::new()
    } else {
        vec![
            "the structure's other settings (leaf size, fit, cells, depth) have no words: a \
             step builds it with the defaults"
                .to_owned(),
        ]
    }
}

/// A name as the address and scene files write it.
fn name<T: serde::Serialize>(value: &T) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(word)) => word,
        _ => String::new(),
    }
}

/// Numbers as the address writes them: `0,4.5,1,-0.25` (to a thousandth; no `-0`).
fn numbers_text(numbers: &[Coord]) -> String {
    numbers
        .iter()
        .map(|c| {
            let rounded = (f64::from(c.0) * 1000.0).round() / 1000.0;
            let rounded = if rounded == 0.0 { 0.0 } else { rounded };
            format!("{rounded}")
        })
        .collect::<Vec<_>>()
        .join(",")
}
