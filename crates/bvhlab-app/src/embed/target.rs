//! Where the lab's own messages to its parent go (`ready`, `progress`, `size`, `panic`):
//! `postMessage` needs the receiver's origin as `targetOrigin`, and a browser logs a warning
//! for every message posted to an origin the parent does not have. So the lab posts to the
//! parent's origin once it knows it, and to every allowed origin only while it does not
//! (the embed protocol's rule: the parent hears the lab if its origin is allowed).

/// What the lab knows of its parent's origin, and which origins may script it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ParentOrigin<'a> {
    /// The lab's own origin (`"null"` in a frame sandboxed without `allow-same-origin`).
    pub own: &'a str,
    /// The origins the address names with `origin=`.
    pub named: &'a [String],
    /// The origin of the first command the parent window sent (the surest word).
    pub first_command: Option<&'a str>,
    /// The parent's origin as the browser tells it (`location.ancestorOrigins[0]`, which
    /// Chromium and Safari have), when it does.
    pub ancestor: Option<&'a str>,
}

impl ParentOrigin<'_> {
    /// Whether `origin` may script the lab (and so hear from it).
    fn allows(&self, origin: &str) -> bool {
        origin == self.own || self.named.iter().any(|o| o == origin)
    }

    /// The `targetOrigin`s to post a message to the parent with: its origin when it is
    /// known (none when that origin is not allowed), else every allowed origin. An opaque
    /// origin (`"null"`) cannot be named as a target; a parent of that origin, once it has
    /// scripted the lab, is reached with `"*"`.
    pub fn targets(&self) -> Vec<String> {
        if let Some(origin) = self.first_command {
            // The listener took this command, so its origin is allowed.
            return vec![if origin == "null" { "*" } else { origin }.to_owned()];
        }
        if let Some(origin) = self.ancestor.filter(|o| *o != "null") {
            return if self.allows(origin) {
                vec![origin.to_owned()]
            } else {
                Vec::new()
            };
        }
        let mut all: Vec<String> = Vec::new();
        for origin in std::iter::once(self.own).chain(self.named.iter().map(String::as_str)) {
            if origin != "null" && !all.iter().any(|o| o == origin) {
                all.push(origin.to_owned());
            }
        }
        all
    }
}
