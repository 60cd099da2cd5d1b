//! A lesson being written, as the lesson file's own words: the same keys as
//! `crates/bvhlab-app/lessons/*.toml` ([`super::super::format`] reads them), kept as the
//! teacher typed them, so that writing the file and reading it back gives the same draft.

use serde::{Deserialize, Serialize};

/// A lesson file, as written.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LessonDraft {
    /// Its title.
    pub title: String,
    /// The lecture's section it follows ("§3", "Week 5").
    pub section: String,
    /// Its steps.
    #[serde(rename = "step", default)]
    pub steps: Vec<DraftStep>,
}

impl Default for LessonDraft {
    fn default() -> Self {
        Self {
            title: "My lesson".to_owned(),
            section: "§1".to_owned(),
            steps: Vec::new(),
        }
    }
}

/// One step, as written: the setup and solution in the address's words, each goal as a
/// line like `nodes-visited < 14`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DraftStep {
    /// Its title.
    pub title: String,
    /// Where the lab starts for it.
    pub setup: String,
    /// What it says.
    pub text: String,
    /// The formula or pseudocode it is about.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub formula: Option<String>,
    /// What the student is asked to do.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub task: Option<String>,
    /// The goal's comparisons.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub goal: Vec<String>,
    /// A state that reaches the goal, on top of the setup.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solution: Option<String>,
    /// Why the goal matters.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<String>,
}

/// The lesson file's text.
pub fn to_toml(draft: &LessonDraft) -> String {
    let body = toml::to_string(draft).unwrap_or_else(|e| format!("# not written: {e}\n"));
    format!(
        "# A lesson written in bvh-lab's lesson writer (crates/bvhlab-app/lessons/README.md).\n{body}"
    )
}

/// The draft in the lesson file `text` (called `file`), as its author wrote it.
///
/// # Errors
/// `file:line: why`, when it is not a lesson file's TOML.
pub fn from_toml(file: &str, text: &str) -> Result<LessonDraft, String> {
    toml::from_str(text).map_err(|e| {
        let line = e.span().map_or(0, |s| {
            text.get(..s.start).map_or(0, |t| t.matches('\n').count()) + 1
        });
        format!("{file}:{line}: {}", e.message())
    })
}
