//! What a press, drag, click or key does with the active tool.

use bvhlab::BoundingVolume;
use bvhlab::glam::Vec2;
use egui::PointerButton;

use crate::app::{LabApp, RayHandles};
use crate::scene::{Shape, ShapeKind};
use crate::tool::{BoxGrip, Interaction, RayEnd, Tool};
use crate::volumes::ObbPair;

/// How close (in screen points) a press must be to grab a handle or pick a shape.
const GRAB: f32 = 10.0;
/// This frame's pointer and keyboard input, as the tools need it.
#[allow(clippy::struct_excessive_bools)] // one flag per egui input the tools read
struct Input {
    /// The pointer, in world coordinates.
    pointer: Option<Vec2>,
    /// Where the current press began, in world coordinates.
    press: Option<Vec2>,
    /// The grab distance in world units.
    grab: f32,
    started: bool,
    dragged: bool,
    stopped: bool,
    clicked: bool,
    double_clicked: bool,
    /// The drag's movement this frame, in world units.
    delta: Vec2,
    enter: bool,
    escape: bool,
    delete: bool,
    shift: bool,
}

impl Input {
    fn read(app: &LabApp, ui: &egui::Ui, response: &egui::Response) -> Self {
        let delta = response.drag_delta();
        let (enter, escape, delete, shift) = ui.input(|i| {
            (
                i.key_pressed(egui::Key::Enter),
                i.key_pressed(egui::Key::Escape),
                i.key_pressed(egui::Key::Delete) || i.key_pressed(egui::Key::Backspace),
                i.modifiers.shift,
            )
        });
        Self {
            pointer: response
                .interact_pointer_pos()
                .or(response.hover_pos())
                .map(|p| app.view.to_world(p)),
            press: ui
                .input(|i| i.pointer.press_origin())
                .map(|p| app.view.to_world(p)),
            grab: app.view.world_length(GRAB),
            started: response.drag_started_by(PointerButton::Primary),
            dragged: response.dragged_by(PointerButton::Primary),
            stopped: response.drag_stopped_by(PointerButton::Primary),
            clicked: response.clicked(),
            double_clicked: response.double_clicked(),
            delta: Vec2::new(delta.x, -delta.y) / app.view.scale,
            enter,
            escape,
            delete,
            shift,
        }
    }
}

pub(super) fn handle_tool(app: &mut LabApp, ui: &egui::Ui, response: &egui::Response) {
    let input = Input::read(app, ui, response);
    match app.tool {
        Tool::Pan => {}
        Tool::Ray => ray_tool(app, &input),
        Tool::Point => {
            if (input.clicked || input.dragged)
                && let Some(p) = input.pointer
            {
                app.point = Some(p);
                app.ask_about_point();
            }
        }
        Tool::Segment => segment_tool(app, &input),
        Tool::Polyline | Tool::Polygon => chain_tool(app, &input),
        Tool::Points => points_tool(app, &input),
        Tool::Select => select_tool(app, &input),
        Tool::Obb => obb_tool(app, &input),
    }
    if input.stopped
        && matches!(
            app.interaction,
            Interaction::Ray(_)
                | Interaction::Move(_)
                | Interaction::Box(_)
                | Interaction::Segment(_)
        )
    {
        app.interaction = Interaction::None;
    }
}

fn ray_tool(app: &mut LabApp, input: &Input) {
    if input.started
        && let Some(p0) = input.press
    {
        let near = |q: Vec2| q.distance(p0) <= input.grab;
        app.interaction = match app.ray {
            Some(r) if near(r.origin) => Interaction::Ray(RayEnd::Origin),
            Some(r) if near(r.target) => Interaction::Ray(RayEnd::Target),
            _ => {
                app.ray = Some(RayHandles {
                    origin: p0,
                    target: input.pointer.unwrap_or(p0),
                });
                Interaction::Ray(RayEnd::Target)
            }
        };
    }
    if input.dragged
        && let (Interaction::Ray(end), Some(p), Some(ray)) =
            (&app.interaction, input.pointer, app.ray.as_mut())
    {
        match end {
            RayEnd::Origin => ray.origin = p,
            RayEnd::Target => ray.target = p,
        }
        app.ask_about_ray();
    }
}

fn segment_tool(app: &mut LabApp, input: &Input) {
    if input.started
        && let Some(p0) = input.press
    {
        app.interaction = Interaction::Segment(p0);
    }
    if input.stopped
        && let (Interaction::Segment(a), Some(b)) = (&app.interaction, input.pointer)
    {
        let a = *a;
        app.interaction = Interaction::None;
        if a.distance(b) > input.grab * 0.5 {
            add_shape(app, ShapeKind::Segment, vec![a, b]);
        }
    }
}

fn chain_tool(app: &mut LabApp, input: &Input) {
    let kind = if app.tool == Tool::Polygon {
        ShapeKind::Polygon
    } else {
        ShapeKind::Polyline
    };
    if input.clicked
        && let Some(p) = input.pointer
    {
        match &mut app.interaction {
            Interaction::Chain(points) => {
                // A double-click clicks twice on the same spot: keep one point.
                if points
                    .last()
                    .is_none_or(|&q| q.distance(p) > input.grab * 0.3)
                {
                    points.push(p);
                }
            }
            _ => app.interaction = Interaction::Chain(vec![p]),
        }
    }
    if (input.double_clicked || input.enter)
        && let Interaction::Chain(points) =
            std::mem::replace(&mut app.interaction, Interaction::None)
    {
        add_shape(app, kind, points);
    }
    if input.escape {
        app.interaction = Interaction::None;
    }
}

fn points_tool(app: &mut LabApp, input: &Input) {
    let (true, Some(p)) = (input.clicked, input.pointer) else {
        return;
    };
    match app.interaction {
        Interaction::Cloud(i)
            if app
                .scene
                .shapes()
                .get(i)
                .is_some_and(|s| s.kind == ShapeKind::Points) =>
        {
            app.scene.push_point(i, p);
        }
        _ => {
            if let Some(i) = add_shape(app, ShapeKind::Points, vec![p]) {
                app.interaction = Interaction::Cloud(i);
            }
        }
    }
}

fn select_tool(app: &mut LabApp, input: &Input) {
    if input.clicked
        && let Some(p) = input.pointer
    {
        match (app.scene.pick(p, input.grab), input.shift) {
            (Some(i), true) => {
                if let Some(at) = app.selection.iter().position(|&s| s == i) {
                    app.selection.remove(at);
                } else {
                    app.selection.push(i);
                }
            }
            (Some(i), false) => app.selection = vec![i],
            (None, _) => app.selection.clear(),
        }
    }
    if input.started
        && let Some(p0) = input.press
        && let Some(i) = app.scene.pick(p0, input.grab)
    {
        if !app.selection.contains(&i) {
            app.selection = vec![i];
        }
        app.interaction = Interaction::Move(p0);
    }
    if input.dragged
        && let (Interaction::Move(last), Some(p)) = (&app.interaction, input.pointer)
    {
        let delta = p - *last;
        for &i in &app.selection {
            app.scene.translate(i, delta);
        }
        app.interaction = Interaction::Move(p);
    }
    if input.delete && !app.selection.is_empty() {
        let removed = std::mem::take(&mut app.selection);
        app.scene.remove(&removed);
        app.message = Some(format!("Removed {} shape(s).", removed.len()));
    }
}

fn obb_tool(app: &mut LabApp, input: &Input) {
    let pair = app
        .obb_pair
        .get_or_insert_with(|| ObbPair::around(app.view.center, app.view.world_length(120.0)));
    if input.started
        && let Some(p0) = input.press
    {
        let poses = [pair.a, pair.b];
        app.interaction =
            if let Some(i) = (0..2).find(|&i| poses[i].handle().distance(p0) <= input.grab) {
                Interaction::Box(BoxGrip::Turn(i))
            } else if let Some(i) = (0..2).rev().find(|&i| poses[i].obb().contains(p0)) {
                Interaction::Box(BoxGrip::Move(i))
            } else {
                Interaction::None
            };
    }
    if input.dragged
        && let (Interaction::Box(grip), Some(p)) = (&app.interaction, input.pointer)
    {
        match *grip {
            BoxGrip::Move(i) => pose_mut(pair, i).center += input.delta,
            BoxGrip::Turn(i) => {
                let pose = pose_mut(pair, i);
                let d = p - pose.center;
                if d.length_squared() > 0.0 {
                    pose.angle = d.y.atan2(d.x);
                }
            }
        }
    }
}

fn pose_mut(pair: &mut ObbPair, i: usize) -> &mut crate::volumes::BoxPose {
    if i == 0 { &mut pair.a } else { &mut pair.b }
}

/// Adds a shape, or says why not; returns its index.
fn add_shape(app: &mut LabApp, kind: ShapeKind, points: Vec<Vec2>) -> Option<usize> {
    match Shape::new(kind, points) {
        Ok(shape) => {
            app.message = None;
            Some(app.scene.add(shape))
        }
        Err(e) => {
            app.message = Some(e);
            None
        }
    }
}
