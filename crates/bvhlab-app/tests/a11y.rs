//! The lab for assistive technology, without a browser: egui's accessibility tree of real lab
//! frames, mirrored into a model of the page's elements (`Page`, which applies the mirror's
//! operations as `web/a11y.rs` applies them to the DOM), and what a person does to those
//! elements sent back as the requests egui answers.

use std::collections::{BTreeMap, HashMap};

use bvhlab_app::LabApp;
use bvhlab_app::a11y::events::{PageEvent, requests};
use bvhlab_app::a11y::mirror::{DomOp, Mirror};
use egui::accesskit::NodeId;
use egui::{RawInput, Rect, pos2, vec2};

/// One element of the page model.
#[derive(Clone, Debug, PartialEq)]
struct El {
    tag: &'static str,
    attrs: BTreeMap<&'static str, String>,
    text: Option<String>,
    children: Vec<NodeId>,
    rect: [f64; 4],
}

/// The page's elements, as the operations leave them.
#[derive(Clone, Debug, Default, PartialEq)]
struct Page {
    elements: HashMap<NodeId, El>,
    top: Vec<NodeId>,
    focus: Option<NodeId>,
}

impl Page {
    fn apply(&mut self, ops: &[DomOp]) {
        for op in ops {
            match op {
                DomOp::Create { node, tag } => {
                    let made = El {
                        tag,
                        attrs: BTreeMap::new(),
                        text: None,
                        children: Vec::new(),
                        rect: [0.0; 4],
                    };
                    assert!(
                        self.elements.insert(*node, made).is_none(),
                        "{node:?} made twice"
                    );
                }
                DomOp::Set { node, name, value } => {
                    self.el(*node).attrs.insert(name, value.clone());
                }
                DomOp::Unset { node, name } => {
                    assert!(
                        self.el(*node).attrs.remove(name).is_some(),
                        "{node:?}: {name} was not set"
                    );
                }
                DomOp::Text { node, text } => self.el(*node).text = Some(text.clone()),
                DomOp::Place { node, rect } => self.el(*node).rect = *rect,
                DomOp::Children { node, children } => {
                    for child in children {
                        assert!(self.elements.contains_key(child), "{child:?} placed unmade");
                    }
                    match node {
                        Some(node) => self.el(*node).children.clone_from(children),
                        None => self.top.clone_from(children),
                    }
                }
                DomOp::Remove { node } => {
                    assert!(
                        self.elements.remove(node).is_some(),
                        "{node:?} removed twice"
                    );
                }
                DomOp::Focus(node) => self.focus = *node,
            }
        }
    }

    fn el(&mut self, node: NodeId) -> &mut El {
        self.elements
            .get_mut(&node)
            .unwrap_or_else(|| panic!("{node:?} is not made"))
    }

    /// The elements reachable from the container, each once.
    fn reachable(&self) -> Vec<NodeId> {
        let mut out = Vec::new();
        let mut stack: Vec<NodeId> = self.top.iter().rev().copied().collect();
        while let Some(id) = stack.pop() {
            assert!(!out.contains(&id), "{id:?} is in the page twice");
            out.push(id);
            stack.extend(self.elements[&id].children.iter().rev().copied());
        }
        out
    }

    /// An element's accessible name, as a browser computes it for these elements: the
    /// elements `aria-labelledby` names (their own names, space-separated), else `aria-label`,
    /// else its text.
    fn name(&self, e: &El) -> Option<String> {
        if let Some(ids) = e.attrs.get("aria-labelledby") {
            let parts: Vec<String> = ids
                .split(' ')
                .filter_map(bvhlab_app::a11y::mirror::node_of)
                .filter_map(|n| self.elements.get(&n))
                .filter_map(|e| e.attrs.get("aria-label").or(e.text.as_ref()).cloned())
                .collect();
            return Some(parts.join(" "));
        }
        e.attrs.get("aria-label").or(e.text.as_ref()).cloned()
    }

    /// The one element whose accessible name is `name`.
    fn named(&self, name: &str) -> (NodeId, &El) {
        let found: Vec<(NodeId, &El)> = self
            .elements
            .iter()
            .filter(|(_, e)| self.name(e).as_deref() == Some(name))
            .map(|(id, e)| (*id, e))
            .collect();
        assert_eq!(found.len(), 1, "one element named {name:?}: {found:#?}");
        found[0]
    }
}

/// The lab, egui, the mirror and the page.
struct Run {
    ctx: egui::Context,
    app: LabApp,
    mirror: Mirror,
    page: Page,
    events: Vec<egui::Event>,
    /// The last tree update.
    last: Option<egui::accesskit::TreeUpdate>,
}

impl Run {
    fn new(app: LabApp) -> Self {
        let ctx = egui::Context::default();
        ctx.enable_accesskit();
        let mut run = Self {
            ctx,
            app,
            mirror: Mirror::new(),
            page: Page::default(),
            events: Vec::new(),
            last: None,
        };
        run.settle();
        run
    }

    /// One frame: what changed on the page.
    fn frame(&mut self) -> Vec<DomOp> {
        let input = RawInput {
            screen_rect: Some(Rect::from_min_size(pos2(0.0, 0.0), vec2(1600.0, 1200.0))),
            events: std::mem::take(&mut self.events),
            ..RawInput::default()
        };
        let app = &mut self.app;
        let mut output = self.ctx.run_ui(input, |ui| app.show(ui));
        output.textures_delta.clear();
        let update = output
            .platform_output
            .accesskit_update
            .take()
            .expect("egui gives a tree update each frame once asked");
        self.last = Some(update.clone());
        self.mirror.update(update);
        let ops = self.mirror.changes();
        self.page.apply(&ops);
        ops
    }

    /// Frames until the lab settles (layout, the view fitted, builds).
    fn settle(&mut self) {
        for _ in 0..4 {
            self.frame();
        }
    }

    /// Sends what a person did to an element, then lets the lab settle.
    fn act(&mut self, node: NodeId, event: PageEvent) {
        let requests = requests(node, event);
        assert!(!requests.is_empty(), "a request for a sensible event");
        self.events.extend(requests);
        self.settle();
    }
}

#[test]
fn the_page_reads_as_the_tree_and_a_still_frame_changes_nothing() {
    let mut run = Run::new(LabApp::default());
    let shown = run.page.reachable();
    assert_eq!(shown.len(), run.page.elements.len(), "no element left over");
    assert!(shown.len() > 100, "{} elements", shown.len());
    assert_eq!(shown.len(), run.mirror.len());
    // Nothing moved: nothing to do, so a frame costs the page nothing (but the status bar's
    // frame time, which changes with every frame).
    let ops = run.frame();
    let clock = run
        .page
        .elements
        .iter()
        .find(|(_, e)| e.text.as_deref().is_some_and(|t| t.starts_with("frame ")))
        .map(|(id, _)| *id);
    let of_clock = |op: &DomOp| match op {
        DomOp::Text { node, .. } | DomOp::Place { node, .. } => Some(*node) == clock,
        _ => false,
    };
    assert!(
        ops.iter().all(of_clock),
        "a still frame changed the page: {ops:#?}"
    );

    // A mirror made from scratch on the last tree gives the same page as the one kept up
    // to date over the frames before, element for element.
    let mut fresh = Mirror::new();
    fresh.update(run.last.clone().expect("a tree"));
    let mut page = Page::default();
    page.apply(&fresh.changes());
    assert_eq!(page.top, run.page.top);
    assert_eq!(page.elements.len(), run.page.elements.len());
    for (id, element) in &run.page.elements {
        assert_eq!(page.elements.get(id), Some(element), "{id:?}");
    }
}

#[test]
fn controls_are_elements_with_roles_names_and_states() {
    let run = Run::new(LabApp::default());
    let page = &run.page;
    let (_, tab) = page.named("Controls");
    assert_eq!(tab.tag, "button");
    assert_eq!(
        tab.attrs.get("aria-pressed").map(String::as_str),
        Some("true")
    );
    let (_, lessons) = page.named("Lessons");
    assert_eq!(lessons.tag, "button");
    assert!(lessons.attrs.contains_key("aria-expanded"), "{lessons:?}");
    let (_, volumes) = page.named("Show the bounding volumes");
    assert_eq!(
        volumes.attrs.get("role").map(String::as_str),
        Some("checkbox")
    );
    assert_eq!(
        volumes.attrs.get("aria-checked").map(String::as_str),
        Some("false")
    );
    let sliders: Vec<&El> = page
        .elements
        .values()
        .filter(|e| e.attrs.get("type").map(String::as_str) == Some("range"))
        .collect();
    assert!(!sliders.is_empty());
    for slider in sliders {
        assert_eq!(slider.tag, "input");
        assert!(
            slider.attrs.contains_key("aria-label") || slider.attrs.contains_key("aria-labelledby"),
            "{slider:?}"
        );
        assert!(slider.attrs.contains_key("min") && slider.attrs.contains_key("max"));
    }
    let (_, preset) = page.named("Preset AABB tree on a handful of shapes (§3)");
    assert_eq!(
        preset.attrs.get("aria-haspopup").map(String::as_str),
        Some("listbox")
    );
    // Placed where egui drew them: inside the window, with a size.
    for e in page.elements.values().filter(|e| e.tag == "button") {
        let [x, y, w, h] = e.rect;
        assert!(w > 0.0 && h > 0.0 && x > -1e3 && y > -1e3, "{e:?}");
    }
}

#[test]
fn pressing_focusing_and_setting_mirrored_controls_changes_the_lab() {
    let mut run = Run::new(LabApp::default());
    // A check box, pressed as a screen reader's "activate" (or Space) presses it.
    let (volumes, _) = run.page.named("Show the bounding volumes");
    assert!(!run.app.lab().two().display.volumes);
    run.act(volumes, PageEvent::Press);
    assert!(
        run.app.lab().two().display.volumes,
        "the check box reached the lab"
    );
    assert_eq!(
        run.page.elements[&volumes]
            .attrs
            .get("aria-checked")
            .map(String::as_str),
        Some("true"),
        "and the page says so"
    );

    // A collapsing header opens, and a lesson starts from its button.
    let (lessons, _) = run.page.named("Lessons");
    if run.page.elements[&lessons].attrs["aria-expanded"] == "false" {
        run.act(lessons, PageEvent::Press);
    }
    assert_eq!(run.page.elements[&lessons].attrs["aria-expanded"], "true");
    let (first, _) = run
        .page
        .named("1. §1 Queries: why not test every primitive?");
    run.act(first, PageEvent::Press);
    let lesson = run.app.lab().lesson().expect("the lesson opened");
    assert_eq!(lesson.step, 0);

    // The focus follows the page's, and the page hears where egui's focus is.
    let (next, _) = run.page.named("Next");
    run.act(next, PageEvent::Focus);
    assert_eq!(
        run.page.focus,
        Some(next),
        "egui's focus is on the element focused"
    );

    // A slider set to a number.
    let slider = run
        .page
        .elements
        .iter()
        .find(|(_, e)| e.attrs.get("aria-label").map(String::as_str) == Some("k nearest"))
        .filter(|(_, e)| e.attrs.get("type").map(String::as_str) == Some("range"))
        .map(|(id, _)| *id);
    if let Some(slider) = slider {
        run.act(slider, PageEvent::Number(3.0));
        assert_eq!(run.app.lab().two().half.k, 3, "the slider reached the lab");
    }
}
