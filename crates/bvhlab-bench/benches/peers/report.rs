//! The comparison's output: a text table while it runs, then `results.json` (everything
//! measured, with the machine) and `RESULTS.md` (the tables, the ratios to the goals,
//! the disagreements), merging the WebAssembly results of `wasm.json` when present.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use bvhlab_bench::workload::{RayKind, WorkloadSize};
use serde_json::{Value, json};

use crate::measure::{LibResult, Repeats, TOLERANCE};

/// One scene's results.
pub struct SceneResult {
    /// The scene's name.
    pub name: &'static str,
    /// Its triangle count.
    pub triangles: usize,
    /// Rays per kind.
    pub rays: Vec<(RayKind, usize)>,
    /// Closest-point queries.
    pub points: usize,
    /// One row per library, bvhlab first.
    pub rows: Vec<LibResult>,
}

/// A whole run.
pub struct Run {
    quick: bool,
    size: WorkloadSize,
    repeats: usize,
    /// The scenes measured.
    pub scenes: Vec<SceneResult>,
}

impl Run {
    /// An empty run with its settings.
    pub fn new(quick: bool, size: &WorkloadSize, repeats: Repeats) -> Self {
        Self {
            quick,
            size: *size,
            repeats: repeats.count,
            scenes: Vec::new(),
        }
    }
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or_else(|| "n/a".into(), |x| format!("{x:.digits$}"))
}

/// The header of the running text table.
pub fn header_text() -> String {
    format!(
        "{:<34} {:>9} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>10} {:>10} {:>9}",
        "library",
        "build ms",
        "SAH",
        "B/tri",
        "primary",
        "shadow",
        "occluded",
        "diffuse",
        "random",
        "overview",
        "nodes/ray",
        "prims/ray",
        "cp kq/s"
    )
}

/// One library's line of the running text table (Mrays/s per kind; nodes and primitives
/// per ray of the diffuse rays).
pub fn row_text(r: &LibResult, triangles: usize) -> String {
    let mrays = |k: RayKind| r.kinds.iter().find(|x| x.kind == k).map(|x| x.mrays_per_s);
    let diffuse = r.kinds.iter().find(|x| x.kind == RayKind::Diffuse);
    let occluded = r
        .kinds
        .iter()
        .find_map(|x| x.occlusion.map(|o| o.mrays_per_s));
    let mut line = format!(
        "{:<34} {:>9.1} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>10} {:>10} {:>9}",
        r.library,
        r.build_ms,
        opt(r.facts.sah, 1),
        opt(r.facts.bytes.map(|b| b as f64 / triangles as f64), 0),
        opt(mrays(RayKind::Primary), 2),
        opt(mrays(RayKind::Shadow), 2),
        opt(occluded, 2),
        opt(mrays(RayKind::Diffuse), 2),
        opt(mrays(RayKind::Random), 2),
        opt(mrays(RayKind::Overview), 2),
        opt(diffuse.and_then(|d| d.nodes_per_ray), 1),
        opt(diffuse.and_then(|d| d.prims_per_ray), 1),
        opt(r.closest_per_s.map(|q| q / 1e3), 0),
    );
    let wrong: usize = r
        .kinds
        .iter()
        .map(|k| k.disagreements + k.occlusion.map_or(0, |o| o.disagreements))
        .sum();
    if wrong > 0 || r.closest_disagreements.is_some_and(|n| n > 0) {
        let _ = write!(
            line,
            "  [disagreements: rays {wrong}, closest {}]",
            r.closest_disagreements.unwrap_or(0)
        );
    }
    line
}

fn command_line(cmd: &str, args: &[&str]) -> String {
    Command::new(cmd)
        .args(args)
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_default()
}

fn machine() -> Value {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| {
            l.strip_prefix("model name")
                .map(|m| m.trim_start_matches([' ', '\t', ':']).to_owned())
        })
        .unwrap_or_default();
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let pinned = status
        .lines()
        .find_map(|l| {
            l.strip_prefix("Cpus_allowed_list:")
                .map(|s| s.trim().to_owned())
        })
        .unwrap_or_default();
    json!({
        "cpu": model,
        "cores": cpuinfo.lines().filter(|l| l.starts_with("processor")).count(),
        "cpus_allowed": pinned,
        "rustc": command_line("rustc", &["--version"]),
        "date": command_line("date", &["-u", "+%Y-%m-%d %H:%M UTC"]),
        "rustflags": std::env::var("RUSTFLAGS").unwrap_or_default(),
        "profile": "cargo bench (release, debug info)",
        "avx2": cfg!(target_feature = "avx2"),
    })
}

fn lib_json(r: &LibResult, triangles: usize) -> Value {
    let kinds: Vec<Value> = r
        .kinds
        .iter()
        .map(|k| {
            json!({
                "kind": k.kind.name(), "rays": k.rays, "hits": k.hits,
                "mrays_per_s": k.mrays_per_s, "nodes_per_ray": k.nodes_per_ray,
                "prims_per_ray": k.prims_per_ray, "disagreements": k.disagreements,
                "missed": k.missed,
                "occluded_mrays_per_s": k.occlusion.map(|o| o.mrays_per_s),
                "occluded_rays": k.occlusion.map(|o| o.blocked),
                "occlusion_disagreements": k.occlusion.map(|o| o.disagreements),
                "examples": k.examples.iter().map(|(i, a, b)| json!([i, a, b])).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "library": r.library,
        "build_ms": r.build_ms,
        "build_ms_per_mtri": r.build_ms / (triangles as f64 / 1e6),
        "nodes": r.facts.nodes,
        "sah_cost": r.facts.sah,
        "bytes": r.facts.bytes,
        "bytes_per_triangle": r.facts.bytes.map(|b| b as f64 / triangles as f64),
        "rays": kinds,
        "closest_per_s": r.closest_per_s,
        "closest_disagreements": r.closest_disagreements,
        "closest_examples": r.closest_examples.iter().map(|(i, a, b)| json!([i, a, b])).collect::<Vec<_>>(),
    })
}

/// A JSON file's value, if it is there and parses.
fn read_json(path: &Path) -> Option<Value> {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
}

/// Writes the `--parallel` run's scenes into `dir/parallel.json`, and renders `RESULTS.md`
/// again from `dir/results.json` (when a single-threaded run left one) with them.
///
/// # Errors
/// When a file cannot be written.
pub fn write_parallel(scenes: &[Value], dir: &Path) -> std::io::Result<String> {
    std::fs::create_dir_all(dir)?;
    let parallel = json!({
        "cores": std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
        "date": machine()["date"],
        "scenes": scenes,
    });
    let path = dir.join("parallel.json");
    std::fs::write(
        &path,
        serde_json::to_string_pretty(&parallel).unwrap_or_default(),
    )?;
    let Some(mut all) = read_json(&dir.join("results.json")) else {
        return Ok(path.display().to_string());
    };
    all["parallel"] = parallel;
    let md = dir.join("RESULTS.md");
    std::fs::write(&md, crate::report_md::markdown(&all))?;
    std::fs::write(
        dir.join("results.json"),
        serde_json::to_string_pretty(&all).unwrap_or_default(),
    )?;
    Ok(format!("{} and {}", path.display(), md.display()))
}

/// Writes `results.json` and `RESULTS.md` into `dir`, reading `dir/wasm.json` and
/// `dir/parallel.json` if present.
///
/// # Errors
/// When a file cannot be written.
pub fn write(run: &Run, dir: &Path) -> std::io::Result<String> {
    std::fs::create_dir_all(dir)?;
    let wasm = read_json(&dir.join("wasm.json"));
    let parallel = read_json(&dir.join("parallel.json"));
    let scenes: Vec<Value> = run
        .scenes
        .iter()
        .map(|s| {
            json!({
                "scene": s.name, "triangles": s.triangles, "points": s.points,
                "rays": s.rays.iter().map(|(k, n)| json!({"kind": k.name(), "count": n})).collect::<Vec<_>>(),
                "libraries": s.rows.iter().map(|r| lib_json(r, s.triangles)).collect::<Vec<_>>(),
            })
        })
        .collect();
    let all = json!({
        "machine": machine(),
        "mode": if run.quick { "quick" } else { "full" },
        "repeats": run.repeats,
        "tolerance": TOLERANCE,
        "workload": {
            "camera": [run.size.width, run.size.height], "viewpoints": run.size.viewpoints,
            "random_rays": run.size.random_rays, "points": run.size.points,
        },
        "native": scenes,
        "wasm": wasm,
        "parallel": parallel,
    });
    let json_text = serde_json::to_string_pretty(&all).unwrap_or_default();
    std::fs::write(dir.join("results.json"), json_text)?;
    std::fs::write(dir.join("RESULTS.md"), crate::report_md::markdown(&all))?;
    Ok(format!(
        "{0}/results.json and {0}/RESULTS.md",
        dir.display()
    ))
}
