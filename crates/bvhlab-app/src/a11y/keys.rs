//! What a key pressed on an element of the mirror does: what the browser does with it itself
//! (Tab moves the focus, Enter and Space press a button, the arrows move a slider, typing goes
//! into a text field), what goes on to the lab as a key press (its shortcuts: `.` and `,` step,
//! R and the arrows move the ray on the drawing, `[` and `]` turn a lesson's pages, P, H, 1-9),
//! and the two keys that leave: Tab after the last element (the browser's own doing), and
//! Escape from anywhere, when no popup is open to close (WCAG 2.1.2, no keyboard trap).

/// The kind of element a key lands on, as far as keys are concerned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// A `<button>` (buttons, check boxes, radio buttons, collapsing headers, combo boxes).
    Button,
    /// A slider or a number field: the arrows, Home, End, Page Up and Down are its own.
    Range,
    /// A text field: every printable key and the editing keys are its own.
    Text,
    /// A panel's edge: the arrows resize the panel.
    Separator,
    /// The drawing: every key but Tab goes to the lab.
    Drawing,
    /// Anything else focusable (a tree diagram's node, a group).
    Other,
}

impl Target {
    /// The target for an element of tag `tag`, `type` attribute `kind` and role `role`.
    pub fn of(tag: &str, kind: Option<&str>, role: Option<&str>) -> Self {
        match (tag, kind, role) {
            ("button", _, _) => Self::Button,
            ("input", Some("range" | "number"), _) => Self::Range,
            ("input" | "textarea", _, _) => Self::Text,
            (_, _, Some("separator")) => Self::Separator,
            (_, _, Some("application")) => Self::Drawing,
            _ => Self::Other,
        }
    }
}

/// What a key press does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// The browser's own: the element handles it (and Tab moves the focus).
    Native,
    /// A key press for the lab (its shortcuts), and not the browser's (no scrolling).
    Lab,
    /// Resize: one step (`+1` or `-1`) of the separator.
    Step(i32),
    /// Leave the lab: the focus goes after its last element, so that the next Tab leaves it.
    Leave,
}

/// Where the key `key` (a `KeyboardEvent.key`) goes on `target`; `popup` says whether the lab
/// has a popup open (Escape then closes it instead of leaving).
pub fn route(target: Target, key: &str, popup: bool) -> Route {
    match key {
        "Tab" => return Route::Native,
        "Escape" if popup => return Route::Lab,
        "Escape" => return Route::Leave,
        _ => {}
    }
    match target {
        Target::Button if matches!(key, "Enter" | " ") => Route::Native,
        Target::Range
            if matches!(
                key,
                "ArrowLeft"
                    | "ArrowRight"
                    | "ArrowUp"
                    | "ArrowDown"
                    | "Home"
                    | "End"
                    | "PageUp"
                    | "PageDown"
            ) || key.chars().count() == 1
                || matches!(key, "Backspace" | "Delete" | "Enter") =>
        {
            Route::Native
        }
        Target::Text => Route::Native,
        Target::Separator => match key {
            "ArrowLeft" | "ArrowUp" => Route::Step(-1),
            "ArrowRight" | "ArrowDown" => Route::Step(1),
            _ => Route::Lab,
        },
        _ => Route::Lab,
    }
}
