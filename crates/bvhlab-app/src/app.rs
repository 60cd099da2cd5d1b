//! The lab's frame: the model ([`Lab`]), the UI's own state ([`UiState`]), and the layout
//! (controls on the left in the lecture's order, "Step through" on the right, the tree
//! diagram and a status line below, the canvas or 3D view in the middle).
//!
//! Each frame the keyboard, dropped files, the panels and the view say what they want as
//! [`Action`]s, and [`LabApp::show`] applies them to the lab once the frame is drawn; the
//! next frame shows the result (a frame is asked for whenever something changed).

use web_time::Instant;

use crate::lessons::writer::{LessonWriter, WriterCommand};
use crate::model::{Action, Action2d, Dimension, Lab, PlaybackAction};
use crate::report::Report;
use crate::ui_state::{Cx, UiState};

/// The lab with its UI.
pub struct LabApp {
    /// The lab's state: changed only through [`LabApp::apply`].
    lab: Lab,
    /// What the UI keeps between frames that is not the lab's state.
    pub ui: UiState,
    /// What the lab last reported to the page.
    pub report: Report,
    /// The lesson a teacher writes, if the writer is open: changed only through
    /// [`LabApp::write`].
    writer: Option<LessonWriter>,
    /// Whether the lab's text sizes and colours are in egui's styles ([`crate::theme`]).
    styled: bool,
}

impl Default for LabApp {
    fn default() -> Self {
        Self::new(Lab::default())
    }
}

impl LabApp {
    /// The lab `lab`, with every panel shown.
    pub fn new(lab: Lab) -> Self {
        Self {
            lab,
            ui: UiState::new(),
            report: Report::default(),
            writer: None,
            styled: false,
        }
    }

    /// The lab, opened on `actions` applied to a fresh one (a preset, a structure, a ray...).
    ///
    /// # Panics
    /// If an action is refused: for tests and examples, whose actions are known to apply.
    pub fn with(actions: impl IntoIterator<Item = Action>) -> Self {
        let mut app = Self::default();
        for action in actions {
            if let Err(e) = app.apply(action.clone()) {
                #[expect(
                    clippy::panic,
                    reason = "a test's setup that cannot apply is a bug in the test"
                )]
                {
                    panic!("{action:?} was refused: {e}");
                }
            }
        }
        app
    }

    /// The lab's state.
    pub fn lab(&self) -> &Lab {
        &self.lab
    }

    /// The 2D canvas's transform as last drawn (its first half when comparing).
    pub fn canvas_screen(&self) -> crate::lab2d::Screen {
        self.ui.canvas.screen(self.lab.two())
    }

    /// Applies `action` to the lab.
    ///
    /// # Errors
    /// Why it was refused; the lab is then unchanged.
    pub fn apply(&mut self, action: impl Into<Action>) -> Result<(), String> {
        self.lab.apply(action.into())
    }

    /// The lesson being written, if the writer is open.
    pub fn writer(&self) -> Option<&LessonWriter> {
        self.writer.as_ref()
    }

    /// Carries out a command of the lesson writer, and the lab actions it asks for.
    ///
    /// # Errors
    /// Why it was refused; the writer (and the lab) are then unchanged.
    pub fn write(&mut self, command: WriterCommand) -> Result<(), String> {
        match command {
            WriterCommand::Start => self.writer = Some(LessonWriter::new(&self.lab)),
            WriterCommand::EditOpen => {
                let teacher = self
                    .lab
                    .lesson()
                    .and_then(|p| p.lesson.teacher.clone())
                    .ok_or("no teacher's lesson is open to edit")?;
                self.writer = Some(LessonWriter::editing(
                    &teacher.file,
                    &teacher.text,
                    &self.lab,
                )?);
            }
            WriterCommand::Close => self.writer = None,
            WriterCommand::Do(action) => {
                let writer = self
                    .writer
                    .as_mut()
                    .ok_or("the lesson writer is not open")?;
                let mut changed = writer.clone();
                let said = say_after(&action);
                let asks = changed.apply(action, &self.lab)?;
                self.lab.apply_all(asks)?;
                // The verdict and the save also go to the status line (and so to screen
                // readers), wherever the writer's pane is scrolled.
                if let Some(said) = said.and_then(|say| say(&changed)) {
                    self.lab.apply(Action::SetMessage(Some(said)))?;
                }
                self.writer = Some(changed);
            }
        }
        Ok(())
    }

    /// Carries out the writer's commands made by the UI in order; a refused one says why in
    /// the status line. Whether any applied.
    fn write_from_ui(&mut self, commands: Vec<WriterCommand>) -> bool {
        let mut changed = false;
        for command in commands {
            match self.write(command) {
                Ok(()) => changed = true,
                Err(e) => changed |= self.say_refused(&e),
            }
        }
        changed
    }

    /// Says in the status line why something the UI asked was refused, as a sentence;
    /// whether the lab took the message.
    fn say_refused(&mut self, why: &str) -> bool {
        let said = crate::persist::capitalized(why);
        let end = if said.ends_with('.') { "" } else { "." };
        self.lab
            .apply(Action::SetMessage(Some(format!("{said}{end}"))))
            .is_ok()
    }

    /// Applies `actions` made by the UI in order. A refused one says why in the status line
    /// (the lab is then as it was before it). Whether any applied.
    fn apply_from_ui(&mut self, actions: Vec<Action>) -> bool {
        let mut changed = false;
        for action in actions {
            match self.lab.apply(action) {
                Ok(()) => changed = true,
                Err(e) => changed |= self.say_refused(&e),
            }
        }
        changed
    }

    /// The lab's whole UI, inside `ui` (the native window, the web canvas, or a test
    /// harness).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        if !self.styled {
            crate::theme::install(ui.ctx());
            self.styled = true;
            // This frame was laid out with the old style.
            ui.ctx().request_repaint();
        }
        let dt = ui.input(|i| f64::from(i.stable_dt));
        self.ui.linked = self.ui.hovered.take();
        // The bounding volumes table says again this frame which row is hovered.
        self.ui.canvas.volume_hover = None;
        self.ui.clock.tick(Instant::now());
        // What happened since the last frame: time passed, keys, files, screenshots.
        let mut actions = vec![Action::Tick {
            seconds: dt,
            build_ms: crate::model::lab3d::build_budget_ms(self.ui.clock.median_ms()),
        }];
        playback_keys(&self.lab, ui, &mut actions);
        edit_keys(&self.lab, ui, &mut actions);
        crate::panels::predict::predict_keys(&self.lab, ui.ctx(), &mut actions);
        crate::panels::lesson::lesson_keys(&self.lab, ui.ctx(), &mut actions);
        actions.extend(crate::persist::poll_imports(ui.ctx()));
        actions.extend(crate::panels::export::finish_png(&mut self.ui, ui.ctx()));
        self.apply_from_ui(actions);

        let mut actions = Vec::new();
        let mut writer_asks = Vec::new();
        let mut cx = Cx {
            lab: &self.lab,
            ui: &mut self.ui,
            actions: &mut actions,
            writer: self.writer.as_ref(),
            writer_asks: &mut writer_asks,
        };
        layout(&mut cx, ui);
        if self.apply_from_ui(actions) | self.write_from_ui(writer_asks) {
            ui.ctx().request_repaint();
        }
        if self.lab.playing() || self.lab.busy() || self.lab.animating() {
            ui.ctx().request_repaint();
        }
        self.report = Report::of(&self.lab, &self.ui);
        if let Some(id) = self.ui.drawing {
            crate::a11y::describe::drawing(ui.ctx(), id, self.lab.dimension(), &self.report);
        }
    }

    /// Replaces the lab (a crash's recovery) and starts the UI afresh, keeping its renderer
    /// and which panels are shown.
    pub fn replace_lab(&mut self, lab: Lab) {
        let old = std::mem::replace(&mut self.ui, UiState::new());
        self.ui.renderer = old.renderer;
        self.ui.render_state = old.render_state;
        self.ui.panels = old.panels;
        self.lab = lab;
    }
}

/// Below this window width (points) the side panels keep to their share of it.
pub const NARROW: f32 = 1100.0;

/// Below this window width (points) the controls and "Step through" share one panel, as
/// tabs (a 1280 px laptop gave the view a third of its width with both beside it).
pub const COMPACT: f32 = 1500.0;

/// The controls (left) and "Step through" (right), each where shown. Narrow windows (an
/// embedded lab) give the panels less, so the view keeps room: below NARROW the panels may
/// not grow past their share (their widest rows scroll or clip), or an 800 px embed left the
/// view 70 px.
fn side_panels(cx: &mut Cx<'_>, ui: &mut egui::Ui, width: f32) {
    let (controls_max, stepper_max) = if width < NARROW {
        (width * 0.3, width * 0.32)
    } else {
        (f32::INFINITY, f32::INFINITY)
    };
    if cx.ui.panels.controls {
        egui::Panel::left("controls")
            .resizable(true)
            .default_size((width * 0.3).clamp(220.0, 340.0))
            .max_size(controls_max.max(160.0))
            .show(ui, |ui| {
                crate::panels::controls(cx, ui, !cx.ui.panels.stepper);
            });
    }
    if cx.ui.panels.stepper {
        egui::Panel::right("stepper")
            .resizable(true)
            .default_size((width * 0.4).clamp(240.0, 440.0))
            .max_size(stepper_max.max(160.0))
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .show(ui, |ui| crate::panels::step_through::step_through(cx, ui));
            });
    }
}

/// The controls and "Step through" as two tabs of one panel.
fn side_tabs(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    use crate::address::SideTab;
    ui.horizontal(|ui| {
        let tab = &mut cx.ui.panels.tab;
        ui.selectable_value(tab, SideTab::Controls, "Lessons and controls");
        ui.selectable_value(tab, SideTab::Stepper, "Step through");
    });
    ui.separator();
    match cx.ui.panels.tab {
        SideTab::Controls => crate::panels::controls(cx, ui, true),
        SideTab::Stepper => {
            egui::ScrollArea::vertical()
                .id_salt("stepper tab")
                .show(ui, |ui| crate::panels::step_through::step_through(cx, ui));
        }
    }
}

/// The panels around the view, and the view.
fn layout(cx: &mut Cx<'_>, ui: &mut egui::Ui) {
    let three = cx.lab.dimension() == Dimension::Three;
    let width = ui.available_width();
    let shared = width < COMPACT && cx.ui.panels.controls && cx.ui.panels.stepper;
    egui::Panel::bottom("status").show(ui, |ui| {
        crate::panels::status::status_line(cx, ui, shared);
    });
    if shared {
        // A laptop's window: the controls and "Step through" share one panel, as tabs, so
        // that the view keeps most of the width.
        egui::Panel::left("side")
            .resizable(true)
            .default_size((width * 0.34).clamp(300.0, 440.0))
            .max_size((width * 0.45).max(200.0))
            .show(ui, |ui| side_tabs(cx, ui));
    } else {
        side_panels(cx, ui, width);
    }
    if cx.ui.panels.tree_in(cx.lab.dimension()) {
        egui::Panel::bottom("tree")
            .resizable(true)
            // A short window (an embedded lab) starts it at under a third of its height
            // (the view above it gives a row to the legend).
            .default_size(
                crate::panels::tree::DEFAULT_PANEL_HEIGHT
                    .min(ui.available_height() * 0.3)
                    .max(crate::panels::tree::MIN_PANEL_HEIGHT),
            )
            .min_size(crate::panels::tree::MIN_PANEL_HEIGHT)
            .show(ui, |ui| crate::panels::tree::tree_panel(cx, ui));
    } else {
        cx.ui.tree_rect = None;
    }
    egui::CentralPanel::default()
        .frame(egui::Frame::NONE.fill(crate::lab3d::BACKGROUND))
        .show(ui, |ui| {
            crate::legend::strip(cx, ui);
            if three {
                crate::lab3d::view(cx, ui);
            } else {
                crate::lab2d::canvas(cx, ui);
            }
        });
}

/// Keyboard playback, when no text field has the focus: `.` one step forward, `,` one
/// back, Home and End, Space to play or pause; H shows or hides the 3D view's heat map.
fn playback_keys(lab: &Lab, ui: &egui::Ui, actions: &mut Vec<Action>) {
    if ui.ctx().text_edit_focused() {
        return;
    }
    ui.input(|i| {
        // Jumps first, then steps: "Home . ." in one frame means step 2.
        if i.key_pressed(egui::Key::Home) {
            actions.push(PlaybackAction::GoTo(0).into());
        }
        if i.key_pressed(egui::Key::End) {
            actions.push(PlaybackAction::End.into());
        }
        // Several presses can arrive in one frame (fast typing, a slow frame).
        let forward = i.num_presses(egui::Key::Period);
        let back = i.num_presses(egui::Key::Comma);
        if forward + back > 0 {
            actions.push(PlaybackAction::StepBy(forward as isize - back as isize).into());
        }
        if i.key_pressed(egui::Key::Space) {
            actions.push(PlaybackAction::Toggle.into());
        }
        if lab.dimension() == Dimension::Three && i.key_pressed(egui::Key::H) {
            let mut heat = lab.three().heat;
            heat.on = !heat.on;
            actions.push(crate::model::Action3d::SetHeat(heat).into());
        }
    });
}

/// Undo (Ctrl+Z, Cmd+Z on a Mac) and redo (Ctrl+Shift+Z or Ctrl+Y) of the 2D scene's edits,
/// when the 2D half is shown and no text field has the focus (a text field undoes its own
/// typing).
fn edit_keys(lab: &Lab, ui: &egui::Ui, actions: &mut Vec<Action>) {
    if lab.dimension() != Dimension::Two || ui.ctx().text_edit_focused() {
        return;
    }
    let command = egui::Modifiers::COMMAND;
    ui.input_mut(|i| {
        // The longer shortcut first: Ctrl+Z would also match Ctrl+Shift+Z.
        if i.consume_key(command | egui::Modifiers::SHIFT, egui::Key::Z)
            || i.consume_key(command, egui::Key::Y)
        {
            actions.push(Action2d::Redo.into());
        } else if i.consume_key(command, egui::Key::Z) {
            actions.push(Action2d::Undo.into());
        }
    });
}

impl eframe::App for LabApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if self.ui.renderer.is_none() {
            self.ui.renderer = Some(renderer_name(frame));
            self.ui.render_state = frame.wgpu_render_state().cloned();
            if let Some(state) = &self.ui.render_state {
                // eframe's default options: one sample, no depth buffer in egui's pass.
                let target = crate::render3d::gpu::EguiTarget::new(state.target_format);
                crate::render3d::gpu::install(state, target);
            }
        }
        if let Some(seconds) = frame.info().cpu_usage {
            self.ui.clock.record_cpu(f64::from(seconds) * 1e3);
        }
        self.show(ui);
        #[cfg(target_arch = "wasm32")]
        crate::web::publish(&self.report);
    }
}

/// The name of the graphics backend eframe chose.
fn renderer_name(frame: &eframe::Frame) -> String {
    use eframe::wgpu::Backend;
    frame.wgpu_render_state().map_or_else(
        || "none".to_owned(),
        |state| match state.adapter.get_info().backend {
            Backend::BrowserWebGpu => "WebGPU".to_owned(),
            Backend::Gl if cfg!(target_arch = "wasm32") => "WebGL2".to_owned(),
            other => format!("{other:?}"),
        },
    )
}

/// What the status line says after a writer's action, read from the writer after it.
type Say = fn(&LessonWriter) -> Option<String>;

/// The status line's words after `action`, if it has any: the check's verdict, or the step
/// saved.
fn say_after(action: &crate::lessons::writer::WriterAction) -> Option<Say> {
    use crate::lessons::writer::WriterAction;
    match action {
        WriterAction::Check => Some(|w: &LessonWriter| {
            w.verdict.as_ref().map(|v| match v {
                Ok(passed) => format!("The step passed its check: {passed} Save it to keep it."),
                Err(why) => format!("The step is not ready: {why}"),
            })
        }),
        WriterAction::SaveStep => Some(|w: &LessonWriter| {
            let steps = w.draft.steps.len();
            Some(format!(
                "Step saved: the lesson has {steps} step{}. The next step starts from what the \
                 lab shows.",
                crate::model::dimension::plural(steps)
            ))
        }),
        _ => None,
    }
}
