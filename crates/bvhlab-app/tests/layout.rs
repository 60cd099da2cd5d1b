//! The shape of the lab's code, as the redesign (issue 17) left it: the model knows nothing of
//! egui or of the views that read it, and no source file grows past 500 lines.

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("a readable source folder") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// The modules of the lab that draw, or run the page, or hold UI state: the model may not
/// use them.
const VIEWS: [&str; 12] = [
    "crate::app",
    "crate::panels",
    "crate::lab2d",
    "crate::lab3d",
    "crate::render3d",
    "crate::tree_diagram",
    "crate::ui_state",
    "crate::export",
    "crate::embed",
    "crate::persist",
    "crate::report",
    "crate::paint",
];

#[test]
fn the_model_uses_neither_egui_nor_the_views() {
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/model");
    let files = sources(&model);
    assert!(files.len() > 10, "the model's files: {files:?}");
    for file in files {
        let text = std::fs::read_to_string(&file).expect("readable");
        // Code lines only: the docs may say what the views do with the model.
        for (i, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            for word in ["egui", "eframe", "wgpu"] {
                assert!(
                    !code.contains(word),
                    "{}:{}: the model uses {word}: {line}",
                    file.display(),
                    i + 1
                );
            }
            for view in VIEWS {
                assert!(
                    !code.contains(view),
                    "{}:{}: the model uses {view}: {line}",
                    file.display(),
                    i + 1
                );
            }
        }
    }
}

/// The lines of code (not comments) of every file under `src/<dir>`, with where they are.
fn code_lines(dir: &str) -> Vec<(String, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(dir);
    let mut out = Vec::new();
    for file in sources(&root) {
        let text = std::fs::read_to_string(&file).expect("readable");
        for (i, line) in text.lines().enumerate() {
            if !line.trim_start().starts_with("//") {
                out.push((format!("{}:{}", file.display(), i + 1), line.to_owned()));
            }
        }
    }
    out
}

#[test]
fn the_address_sits_below_the_lessons_and_the_embedding() {
    // The address's words (`StartParams`, the panels) are read by `lessons/` (each step's
    // setup) and by `embed/` (what a page opens with): they may use neither, nor the views,
    // nor egui, so that the lab's model builds without them. The scene format's names
    // (`persist`) they share with scene files.
    let lines = code_lines("address");
    assert!(
        lines.len() > 100,
        "the address's code: {} lines",
        lines.len()
    );
    let below = VIEWS.into_iter().filter(|view| *view != "crate::persist");
    let forbidden: Vec<&str> = ["crate::lessons", "egui", "eframe", "wgpu"]
        .into_iter()
        .chain(below)
        .collect();
    for (at, line) in lines {
        for &word in &forbidden {
            assert!(
                !line.contains(word),
                "{at}: the address uses {word}: {line}"
            );
        }
    }
}

#[test]
fn no_source_file_is_over_500_lines() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut long = Vec::new();
    let mut count = 0;
    for entry in std::fs::read_dir(&crates).expect("the crates folder") {
        let src = entry.expect("an entry").path().join("src");
        if !src.is_dir() {
            continue;
        }
        for file in sources(&src) {
            count += 1;
            let lines = std::fs::read_to_string(&file)
                .expect("readable")
                .lines()
                .count();
            if lines > 500 {
                long.push(format!("{}: {lines} lines", file.display()));
            }
        }
    }
    assert!(count > 100, "found {count} source files");
    assert!(long.is_empty(), "over 500 lines: {long:#?}");
}
