//! What element of the page each node of egui's accessibility tree becomes: the tag, the
//! ARIA role where the tag's own is not it, and the attributes that carry its name and state.
//!
//! Native elements where the browser gives the keyboard behaviour for free: a `<button>` is
//! pressed with Enter and Space (so check boxes, radio buttons, toggles and the collapsing
//! headers are buttons with a role and `aria-checked`, `aria-pressed` or `aria-expanded`), a
//! slider is an `<input type="range">` the arrow keys move, a number field an
//! `<input type="number">`, a text field an `<input>` or `<textarea>`. The same choices as
//! AccessKit's own platform adapters and as the parallel DOM of the `PhET` simulations: the
//! state lives in the lab, and each element only reports what a person did to it (see
//! `mirror.rs` and the web side, `web/a11y.rs`).

use egui::accesskit::{Action, Node, Role, Toggled};

/// An element's attributes: name and value, sorted by name once made.
pub type Attrs = Vec<(&'static str, String)>;

/// An element of the mirror, as far as the node decides it.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// The tag (`button`, `input`, `div`, ...).
    pub tag: &'static str,
    /// Attributes, sorted by name: role, name, state, value. `value` stands for the live
    /// property of a form field too.
    pub attrs: Attrs,
    /// The element's own text, for elements that show it (labels, buttons); none where the
    /// name is an attribute.
    pub text: Option<String>,
}

/// What a node is for the mirror.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Not mirrored, nor its descendants: text runs (their label carries the text) and scroll
    /// bars (focus scrolls the panel).
    Skip,
    /// An element ([`element`] says which).
    Shown,
}

/// Whether a node with this role is mirrored.
pub fn kind(role: Role) -> Kind {
    match role {
        Role::TextRun | Role::ScrollBar => Kind::Skip,
        _ => Kind::Shown,
    }
}

/// What names a node: its label, and the element ids of the nodes that label it.
struct Name<'a> {
    label: Option<&'a str>,
    labelled_by: &'a [String],
}

impl Name<'_> {
    /// `aria-labelledby` when other nodes name this one, else `aria-label` when it has a
    /// label.
    fn push(&self, attrs: &mut Attrs) {
        if !self.labelled_by.is_empty() {
            attrs.push(("aria-labelledby", self.labelled_by.join(" ")));
        } else if let Some(label) = self.label {
            attrs.push(("aria-label", label.to_owned()));
        }
    }
}

/// The element for `node`, whose own element id is `own_id`. `labelled_by` are the element ids
/// of the nodes that name it.
pub fn element(node: &Node, own_id: &str, labelled_by: &[String]) -> Element {
    let name = Name {
        label: node.label(),
        labelled_by,
    };
    let mut attrs = Attrs::new();
    let (tag, text) = button(node, own_id, &name, &mut attrs)
        .or_else(|| field(node, &name, &mut attrs))
        .unwrap_or_else(|| other(node, &name, &mut attrs));
    if tag == "button" {
        // A button shows its name as its text; one without text is named by an attribute.
        if text.is_none() {
            name.push(&mut attrs);
        }
        attrs.push(("type", "button".to_owned()));
    }
    if let Some(description) = node.description() {
        attrs.push(("aria-description", description.to_owned()));
    }
    if node.is_disabled() {
        attrs.push(("aria-disabled", "true".to_owned()));
    }
    let natively_focusable = matches!(tag, "button" | "input" | "textarea" | "a");
    if node.supports_action(Action::Focus) && !natively_focusable {
        attrs.push(("tabindex", "0".to_owned()));
    }
    attrs.sort_by(|a, b| a.0.cmp(b.0));
    attrs.dedup_by(|a, b| a.0 == b.0);
    Element { tag, attrs, text }
}

/// The nodes that are `<button>`s: a press is their one action. Their text is their name.
fn button(
    node: &Node,
    own_id: &str,
    name: &Name<'_>,
    attrs: &mut Attrs,
) -> Option<(&'static str, Option<String>)> {
    let label = name.label.map(str::to_owned);
    let checked = |attrs: &mut Attrs| {
        let toggled = node.toggled().unwrap_or(Toggled::False);
        attrs.push(("aria-checked", toggled_word(toggled).to_owned()));
    };
    match node.role() {
        Role::Button | Role::DefaultButton => {
            if let Some(toggled) = node.toggled() {
                attrs.push(("aria-pressed", toggled_word(toggled).to_owned()));
            }
        }
        Role::CheckBox | Role::Switch => {
            let role = if node.role() == Role::Switch {
                "switch"
            } else {
                "checkbox"
            };
            attrs.push(("role", role.to_owned()));
            checked(attrs);
        }
        Role::RadioButton | Role::MenuItemRadio => {
            attrs.push(("role", "radio".to_owned()));
            checked(attrs);
        }
        Role::Tab => {
            attrs.push(("role", "tab".to_owned()));
            let selected = node.is_selected().unwrap_or(false);
            attrs.push(("aria-selected", bool_word(selected).to_owned()));
        }
        Role::DisclosureTriangle => {
            let open = node.is_expanded().unwrap_or(false);
            attrs.push(("aria-expanded", bool_word(open).to_owned()));
        }
        Role::ComboBox => {
            attrs.push(("aria-haspopup", "listbox".to_owned()));
            let open = node.is_expanded().unwrap_or(false);
            attrs.push(("aria-expanded", bool_word(open).to_owned()));
            // A closed combo box shows its choice, and is named by its label and its choice
            // ("Preset AABB tree on ..."), as a select-only combo box is in ARIA's practices.
            let shown = node.value().map(str::to_owned);
            if !name.labelled_by.is_empty() {
                let mut ids = name.labelled_by.to_vec();
                ids.push(own_id.to_owned());
                attrs.push(("aria-labelledby", ids.join(" ")));
            } else if let (Some(label), Some(value)) = (name.label, &shown) {
                attrs.push(("aria-label", format!("{label}: {value}")));
            }
            return Some(("button", shown.or(label)));
        }
        Role::Link => return Some(("a", label)),
        _ => return None,
    }
    Some(("button", label))
}

/// The form fields: sliders, number fields, text fields and a panel's edge.
fn field(
    node: &Node,
    name: &Name<'_>,
    attrs: &mut Attrs,
) -> Option<(&'static str, Option<String>)> {
    let tag = match node.role() {
        Role::Slider => {
            range(node, attrs);
            attrs.push(("type", "range".to_owned()));
            "input"
        }
        Role::SpinButton => {
            range(node, attrs);
            attrs.push(("type", "number".to_owned()));
            "input"
        }
        Role::TextInput | Role::SearchInput | Role::EmailInput | Role::NumberInput => {
            attrs.push(("type", "text".to_owned()));
            text_field(node, attrs);
            "input"
        }
        Role::MultilineTextInput => {
            text_field(node, attrs);
            "textarea"
        }
        Role::Splitter => {
            attrs.push(("role", "separator".to_owned()));
            // A focusable separator is a slider in ARIA: it needs a value.
            let percent = node.numeric_value().map_or(50.0, |v| (v * 100.0).round());
            attrs.push(("aria-valuenow", format!("{percent}")));
            attrs.push(("aria-valuemin", "0".to_owned()));
            attrs.push(("aria-valuemax", "100".to_owned()));
            "div"
        }
        _ => return None,
    };
    name.push(attrs);
    Some((tag, None))
}

/// Text, structure and the drawings.
fn other(node: &Node, name: &Name<'_>, attrs: &mut Attrs) -> (&'static str, Option<String>) {
    // A label's text is its value (egui puts it there), else its name.
    let text = node.value().or(name.label).map(str::to_owned);
    let role = |attrs: &mut Attrs, role: &str| attrs.push(("role", role.to_owned()));
    match node.role() {
        Role::Heading => {
            let level = node.level().unwrap_or(2).clamp(1, 6);
            (["h1", "h2", "h3", "h4", "h5", "h6"][level - 1], text)
        }
        Role::Label | Role::Paragraph => ("p", text),
        Role::ProgressIndicator => {
            role(attrs, "progressbar");
            if let Some(v) = node.numeric_value() {
                attrs.push(("aria-valuenow", format!("{}", (v * 100.0).round())));
                attrs.push(("aria-valuemin", "0".to_owned()));
                attrs.push(("aria-valuemax", "100".to_owned()));
            }
            name.push(attrs);
            ("div", None)
        }
        Role::Tree => {
            role(attrs, "tree");
            name.push(attrs);
            ("div", None)
        }
        Role::TreeItem => {
            role(attrs, "treeitem");
            if let Some(level) = node.level() {
                attrs.push(("aria-level", level.to_string()));
            }
            if let Some(open) = node.is_expanded() {
                attrs.push(("aria-expanded", bool_word(open).to_owned()));
            }
            if let Some(selected) = node.is_selected() {
                attrs.push(("aria-selected", bool_word(selected).to_owned()));
            }
            ("div", text)
        }
        Role::Canvas | Role::Application | Role::Image => {
            // A drawing the lab describes in words: an image for a reader browsing the page,
            // and, when it takes keys, an application that passes them on to the lab.
            if node.supports_action(Action::Focus) {
                role(attrs, "application");
                attrs.push(("aria-roledescription", "drawing".to_owned()));
            } else {
                role(attrs, "img");
            }
            name.push(attrs);
            ("div", None)
        }
        Role::Tooltip => {
            role(attrs, "tooltip");
            ("div", text)
        }
        Role::Alert => {
            role(attrs, "alert");
            ("div", text)
        }
        Role::Group | Role::Region | Role::Figure | Role::Pane | Role::Window
            if name.label.is_some() || !name.labelled_by.is_empty() =>
        {
            let landmark = match node.role() {
                Role::Figure => "figure",
                Role::Group => "group",
                _ => "region",
            };
            role(attrs, landmark);
            name.push(attrs);
            ("div", None)
        }
        _ => {
            // A named container is a group (ARIA names no plain `div`).
            if name.label.is_some() || !name.labelled_by.is_empty() {
                role(attrs, "group");
                name.push(attrs);
            }
            ("div", None)
        }
    }
}

/// A text field's value, hint and whether it can be changed.
fn text_field(node: &Node, attrs: &mut Attrs) {
    attrs.push(("value", node.value().unwrap_or_default().to_owned()));
    if let Some(hint) = node.placeholder() {
        attrs.push(("placeholder", hint.to_owned()));
    }
    if node.is_read_only() {
        attrs.push(("readonly", String::new()));
    }
}

/// A slider's or number field's value and range (`min`, `max`, `step` as the input reads
/// them), and the value as the lab writes it.
fn range(node: &Node, attrs: &mut Attrs) {
    attrs.push(("value", number(node.numeric_value().unwrap_or(0.0))));
    if let Some(min) = node.min_numeric_value() {
        attrs.push(("min", number(min)));
    }
    if let Some(max) = node.max_numeric_value() {
        attrs.push(("max", number(max)));
    }
    let step = node.numeric_value_step().filter(|s| *s > 0.0);
    attrs.push(("step", step.map_or_else(|| "any".to_owned(), number)));
    if let Some(text) = node.value() {
        attrs.push(("aria-valuetext", text.to_owned()));
    }
}

/// A number as an input's attribute takes it.
fn number(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        "0".to_owned()
    }
}

fn toggled_word(toggled: Toggled) -> &'static str {
    match toggled {
        Toggled::True => "true",
        Toggled::False => "false",
        Toggled::Mixed => "mixed",
    }
}

fn bool_word(b: bool) -> &'static str {
    if b { "true" } else { "false" }
}
