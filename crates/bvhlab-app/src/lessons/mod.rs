//! The lessons built into the lab: the files in `crates/bvhlab-app/lessons/`, one lesson
//! each, read once ([`catalog`]). Their format is in that folder's README: TOML, with each
//! step's starting state in the address's words and its goal in a line like
//! `primitives-tested < compare` ([`goal_text`]). A file that cannot be read is refused
//! with its name and line ([`mod@format`]); `tests/lessons.rs` reads every one, so a bad lesson
//! fails the tests before it reaches a page.

pub mod format;
pub mod goal_text;
pub mod open;
pub mod report;
pub mod writer;

use std::sync::{Arc, OnceLock};

use crate::model::Lesson;

mod files {
    include!(concat!(env!("OUT_DIR"), "/lessons.rs"));
}

/// Every lesson file's name and text, in order.
pub fn files() -> &'static [(&'static str, &'static str)] {
    files::FILES
}

/// The lessons, in order, each read from its file, or why a file could not be read.
pub fn catalog() -> &'static [Result<Arc<Lesson>, String>] {
    static CATALOG: OnceLock<Vec<Result<Arc<Lesson>, String>>> = OnceLock::new();
    CATALOG.get_or_init(|| {
        files()
            .iter()
            .map(|(file, text)| format::read(file, text).map(Arc::new))
            .collect()
    })
}

/// The lessons that could be read, in order.
pub fn lessons() -> impl Iterator<Item = &'static Arc<Lesson>> {
    catalog().iter().filter_map(|l| l.as_ref().ok())
}

/// The lesson named `name`.
///
/// # Errors
/// When there is none, naming the lessons there are.
pub fn find(name: &str) -> Result<Arc<Lesson>, String> {
    lessons().find(|l| l.name == name).cloned().ok_or_else(|| {
        let names: Vec<&str> = lessons().map(|l| l.name.as_str()).collect();
        crate::persist::no_such_name("lesson", name, &names)
    })
}
