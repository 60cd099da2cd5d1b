//! What a press, drag, click or key does with the active tool: the drag in progress is the
//! canvas's own ([`Interaction`]); what it does to the lab is said as actions.

use bvhlab::BoundingVolume;
use bvhlab::glam::Vec2;
use egui::PointerButton;

use super::Screen;
use super::interaction::{BoxGrip, Interaction, RayEnd};
use crate::model::Action2d;
use crate::model::lab2d::RayHandles;
use crate::model::scene::ShapeKind;
use crate::model::tools::Tool;
use crate::model::volumes::ObbPair;
use crate::ui_state::Cx;

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
    fn read(screen: &Screen, ui: &egui::Ui, response: &egui::Response) -> Self {
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
                .map(|p| screen.to_world(p)),
            press: ui
                .input(|i| i.pointer.press_origin())
                .map(|p| screen.to_world(p)),
            grab: screen.world_length(GRAB),
            started: response.drag_started_by(PointerButton::Primary),
            dragged: response.dragged_by(PointerButton::Primary),
            stopped: response.drag_stopped_by(PointerButton::Primary),
            clicked: response.clicked(),
            double_clicked: response.double_clicked(),
            delta: Vec2::new(delta.x, -delta.y) / screen.camera.scale,
            enter,
            escape,
            delete,
            shift,
        }
    }
}

pub(super) fn handle_tool(
    cx: &mut Cx<'_>,
    ui: &egui::Ui,
    response: &egui::Response,
    screen: &Screen,
) {
    let input = Input::read(screen, ui, response);
    let mut drag = std::mem::take(&mut cx.ui.canvas.interaction);
    let mut tools = Tools {
        cx,
        drag: &mut drag,
    };
    match tools.cx.lab.two().tool {
        Tool::Pan => {}
        Tool::Ray => tools.ray(&input),
        Tool::Point => {
            if (input.clicked || input.dragged)
                && let Some(p) = input.pointer
            {
                tools.cx.act(Action2d::SetPoint(Some(p)));
            }
        }
        Tool::Segment => tools.segment(&input),
        Tool::Polyline | Tool::Polygon => tools.chain(&input),
        Tool::Points => tools.points(&input),
        Tool::Select => tools.select(&input),
        Tool::Obb => tools.obb(&input),
    }
    if input.stopped
        && matches!(
            drag,
            Interaction::Ray(_)
                | Interaction::Move(_)
                | Interaction::Box(_)
                | Interaction::Segment(_)
        )
    {
        drag = Interaction::None;
    }
    cx.ui.canvas.interaction = drag;
}

/// The tools at work: the lab to read and ask, and the drag in progress.
struct Tools<'a, 'b> {
    cx: &'a mut Cx<'b>,
    drag: &'a mut Interaction,
}

impl Tools<'_, '_> {
    fn ray(&mut self, input: &Input) {
        let current = self.cx.lab.two().ray;
        if input.started
            && let Some(p0) = input.press
        {
            let near = |q: Vec2| q.distance(p0) <= input.grab;
            *self.drag = match current {
                Some(r) if near(r.origin) => Interaction::Ray(RayEnd::Origin),
                Some(r) if near(r.target) => Interaction::Ray(RayEnd::Target),
                _ => {
                    self.cx.act(Action2d::SetRay(Some(RayHandles {
                        origin: p0,
                        target: input.pointer.unwrap_or(p0),
                    })));
                    Interaction::Ray(RayEnd::Target)
                }
            };
            return;
        }
        if input.dragged
            && let (Interaction::Ray(end), Some(p), Some(mut ray)) =
                (&*self.drag, input.pointer, current)
        {
            match end {
                RayEnd::Origin => ray.origin = p,
                RayEnd::Target => ray.target = p,
            }
            self.cx.act(Action2d::SetRay(Some(ray)));
        }
    }

    fn segment(&mut self, input: &Input) {
        if input.started
            && let Some(p0) = input.press
        {
            *self.drag = Interaction::Segment(p0);
        }
        if input.stopped
            && let (Interaction::Segment(a), Some(b)) = (&*self.drag, input.pointer)
        {
            let a = *a;
            *self.drag = Interaction::None;
            if a.distance(b) > input.grab * 0.5 {
                self.cx.act(Action2d::AddShape {
                    kind: ShapeKind::Segment,
                    points: vec![a, b],
                });
            }
        }
    }

    fn chain(&mut self, input: &Input) {
        let kind = if self.cx.lab.two().tool == Tool::Polygon {
            ShapeKind::Polygon
        } else {
            ShapeKind::Polyline
        };
        if input.clicked
            && let Some(p) = input.pointer
        {
            match &mut *self.drag {
                Interaction::Chain(points) => {
                    // A double-click clicks twice on the same spot: keep one point.
                    if points
                        .last()
                        .is_none_or(|&q| q.distance(p) > input.grab * 0.3)
                    {
                        points.push(p);
                    }
                }
                drag => *drag = Interaction::Chain(vec![p]),
            }
        }
        if (input.double_clicked || input.enter)
            && let Interaction::Chain(points) = std::mem::take(self.drag)
        {
            self.cx.act(Action2d::AddShape { kind, points });
        }
        if input.escape {
            *self.drag = Interaction::None;
        }
    }

    fn points(&mut self, input: &Input) {
        let (true, Some(p)) = (input.clicked, input.pointer) else {
            return;
        };
        let shapes = self.cx.lab.two().scene.shapes();
        match *self.drag {
            Interaction::Cloud(i) if shapes.get(i).is_some_and(|s| s.kind == ShapeKind::Points) => {
                self.cx.act(Action2d::AddToCloud { cloud: i, point: p });
            }
            _ => {
                // The new cloud is appended: it will be shape `len`.
                *self.drag = Interaction::Cloud(shapes.len());
                self.cx.act(Action2d::AddShape {
                    kind: ShapeKind::Points,
                    points: vec![p],
                });
            }
        }
    }

    fn select(&mut self, input: &Input) {
        let lab = self.cx.lab.two();
        if input.clicked
            && let Some(p) = input.pointer
        {
            let mut selection = lab.selection.clone();
            match (lab.scene.pick(p, input.grab), input.shift) {
                (Some(i), true) => {
                    if let Some(at) = selection.iter().position(|&s| s == i) {
                        selection.remove(at);
                    } else {
                        selection.push(i);
                    }
                }
                (Some(i), false) => selection = vec![i],
                (None, _) => selection.clear(),
            }
            self.cx.act(Action2d::Select(selection));
        }
        if input.started
            && let Some(p0) = input.press
            && let Some(i) = lab.scene.pick(p0, input.grab)
        {
            // Selecting (even the shapes already selected) makes this drag a new edit, so
            // that two drags are undone one at a time.
            let selection = if lab.selection.contains(&i) {
                lab.selection.clone()
            } else {
                vec![i]
            };
            self.cx.act(Action2d::Select(selection));
            *self.drag = Interaction::Move(p0);
        }
        if input.dragged
            && let (Interaction::Move(last), Some(p)) = (&*self.drag, input.pointer)
        {
            let delta = p - *last;
            if delta != Vec2::ZERO {
                self.cx.act(Action2d::MoveSelection(delta));
            }
            *self.drag = Interaction::Move(p);
        }
        if input.delete && !lab.selection.is_empty() {
            self.cx.act(Action2d::DeleteSelection);
        }
    }

    fn obb(&mut self, input: &Input) {
        // The pair exists once the tool is chosen (the model makes it then).
        let Some(mut pair) = self.cx.lab.two().obb_pair else {
            return;
        };
        if input.started
            && let Some(p0) = input.press
        {
            let poses = [pair.a, pair.b];
            *self.drag =
                if let Some(i) = (0..2).find(|&i| poses[i].handle().distance(p0) <= input.grab) {
                    Interaction::Box(BoxGrip::Turn(i))
                } else if let Some(i) = (0..2).rev().find(|&i| poses[i].obb().contains(p0)) {
                    Interaction::Box(BoxGrip::Move(i))
                } else {
                    Interaction::None
                };
        }
        if input.dragged
            && let (Interaction::Box(grip), Some(p)) = (&*self.drag, input.pointer)
        {
            match *grip {
                BoxGrip::Move(i) => pose_mut(&mut pair, i).center += input.delta,
                BoxGrip::Turn(i) => {
                    let pose = pose_mut(&mut pair, i);
                    let d = p - pose.center;
                    if d.length_squared() > 0.0 {
                        pose.angle = d.y.atan2(d.x);
                    }
                }
            }
            self.cx.act(Action2d::SetObbPair(pair));
        }
    }
}

fn pose_mut(pair: &mut ObbPair, i: usize) -> &mut crate::model::volumes::BoxPose {
    if i == 0 { &mut pair.a } else { &mut pair.b }
}
