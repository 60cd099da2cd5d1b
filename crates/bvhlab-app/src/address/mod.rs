//! The page address's parameters (`index.html?preset=kd-tree&structure=kd-tree&ray=...`): how
//! a course page chooses what an embedded lab opens with, and the words a lesson's step
//! writes its setup in. Every parameter is listed in [`PARAMETERS`]; a value the lab cannot
//! use, or a parameter it does not know, is named in the status line and the rest still
//! applies.
//!
//! The vocabulary sits below its two readers: `lessons/` reads its steps' setups with it, and
//! `embed/` opens the lab the address asks for (`StartParams::apply`, which also opens the
//! lesson it names, is there). It uses only the model and the scene format's names.

pub mod panels;
pub mod words;

use crate::model::Setup;
use crate::model::presets::Preset;
use crate::model::volumes3d::Part3d;
use crate::persist::{STORAGE_KEY, SplitName, StructureName, TaskName, VariantName};
pub use panels::{PanelsShown, PanelsShown as Panels, SideTab};

/// The parameters the lab reads, with what each does (the README's table is this list).
pub const PARAMETERS: [(&str, &str); 19] = [
    (
        "preset",
        "a 2D scene: one of the presets' slugs (kd-tree, quadtree, 10k, ...)",
    ),
    (
        "mesh",
        "opens the 3D view on a built-in mesh (cube, sphere, torus, bunny, ...)",
    ),
    (
        "structure",
        "the structure: brute-force, sphere-tree, aabb-tree, obb-tree, grid, bsp, quadtree, kd-tree",
    ),
    (
        "compare",
        "a second structure shown beside the first, on the same question (same names as structure)",
    ),
    (
        "split",
        "how a BVH (sphere, AABB or OBB tree) splits its nodes: spatial-median, object-median, binned-sah",
    ),
    (
        "task",
        "what is stepped through: first-hit, any-hit, all-hits, nearest, range, build",
    ),
    (
        "ray",
        "the ray: origin and direction, x,y,dx,dy in 2D or x,y,z,dx,dy,dz in 3D",
    ),
    (
        "variant",
        "the algorithm's version: full, lecture (the slide's pseudocode), lecture-pruned",
    ),
    ("point", "the query point: x,y in 2D or x,y,z in 3D"),
    (
        "polygon",
        "adds a polygon to the 2D scene and selects it: its corners x1,y1,x2,y2,... (3 to 64)",
    ),
    (
        "obbs",
        "the separating-axis test's two boxes: in 2D for each centre x,y, half width, half height, angle in degrees (10 numbers); in 3D centre x,y,z, half extents x,y,z, turn about x,y,z in degrees (18 numbers)",
    ),
    (
        "volumes",
        "shows the 3D view's bounding volumes: mesh (of the whole mesh) or brush (of the triangles within the radius of the query point)",
    ),
    (
        "step",
        "the playback step to show (0 is the start); with lesson, the lesson's step (1 is its first)",
    ),
    (
        "lesson",
        "opens a lesson at its step (the Lessons panel lists them: queries, bounding-volumes, ...)",
    ),
    (
        "lesson-url",
        "opens a teacher's lesson file (.toml) from this address: the lab's own server, or one that allows it (CORS); the saved progress in it comes back",
    ),
    (
        "panels",
        "the panels shown beside the view, comma-separated: controls, stepper, tree (none: panels=)",
    ),
    (
        "lab",
        "a name for this lab's saved state, so that two labs on one page keep their own",
    ),
    (
        "origin",
        "an origin allowed to script the lab with postMessage (repeat for more); the lab's own origin always may",
    ),
    (
        "fresh",
        "1: start from these parameters, not from the state saved in this browser",
    ),
];

/// The address's parameters, read.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StartParams {
    /// `preset=`.
    pub preset: Option<Preset>,
    /// `mesh=`: a built-in mesh's slug.
    pub mesh: Option<String>,
    /// `structure=`.
    pub structure: Option<StructureName>,
    /// `compare=`.
    pub compare: Option<StructureName>,
    /// `split=`: how a BVH splits its nodes.
    pub split: Option<SplitName>,
    /// `task=`.
    pub task: Option<TaskName>,
    /// `ray=`: 4 or 6 numbers.
    pub ray: Option<Vec<f32>>,
    /// `variant=`.
    pub variant: Option<VariantName>,
    /// `lesson=`: a lesson's name.
    pub lesson: Option<String>,
    /// `lesson-url=`: the address of a teacher's lesson file.
    pub lesson_url: Option<String>,
    /// `point=`: 2 or 3 numbers.
    pub point: Option<Vec<f32>>,
    /// `polygon=`: a polygon's corners, 2 numbers each.
    pub polygon: Option<Vec<f32>>,
    /// `obbs=`: the two boxes of the separating-axis test, 5 numbers each in 2D, 9 in 3D.
    pub obbs: Option<Vec<f32>>,
    /// `volumes=`: the 3D view's bounding volumes, of the mesh or of the brush.
    pub volumes: Option<Part3d>,
    /// `step=`.
    pub step: Option<usize>,
    /// `panels=`: which of the controls, the stepper and the tree diagram are shown.
    pub panels: Option<Panels>,
    /// `lab=`.
    pub lab: Option<String>,
    /// `origin=`, each.
    pub origins: Vec<String>,
    /// `fresh=1`.
    pub fresh: bool,
    /// `debug=panic`: the scripting API's `panic-for-test` command is allowed (for the
    /// browser test of what a crash shows).
    pub debug_panic: bool,
    /// What could not be read, one sentence each.
    pub problems: Vec<String>,
}

/// The longest value read, in characters (an address can be long; a status line cannot).
const MAX_VALUE_CHARS: usize = 400;

impl StartParams {
    /// Reads the address's query string (with or without its leading `?`).
    pub fn parse(search: &str) -> Self {
        let mut params = Self::default();
        for pair in search.trim_start_matches('?').split('&') {
            if pair.is_empty() {
                continue;
            }
            let (name, value) = pair.split_once('=').unwrap_or((pair, ""));
            let name = decode(name);
            let value = decode(value);
            if value.chars().count() > MAX_VALUE_CHARS {
                params.problems.push(format!(
                    "the address's \"{}\" is longer than {MAX_VALUE_CHARS} characters",
                    short(&name)
                ));
                continue;
            }
            if let Err(problem) = params.read(&name, &value) {
                params.problems.push(problem);
            }
        }
        params
    }

    /// Reads one parameter.
    fn read(&mut self, name: &str, value: &str) -> Result<(), String> {
        match name {
            "preset" => {
                self.preset = Some(Preset::from_slug(value).ok_or_else(|| {
                    let known: Vec<&str> = Preset::ALL.iter().map(|p| p.slug()).collect();
                    unknown("preset", "preset", value, &known)
                })?);
            }
            "mesh" => {
                let known = bvhlab_meshio::builtin::list();
                if !known.iter().any(|b| b.slug == value) {
                    let slugs: Vec<&str> = known.iter().map(|b| b.slug).collect();
                    return Err(unknown("mesh", "mesh", value, &slugs));
                }
                self.mesh = Some(value.to_owned());
            }
            "structure" | "compare" => {
                let structure = StructureName::from_name(value)
                    .ok_or_else(|| unknown(name, "structure", value, StructureName::NAMES))?;
                if name == "structure" {
                    self.structure = Some(structure);
                } else {
                    self.compare = Some(structure);
                }
            }
            "split" => {
                self.split = Some(
                    SplitName::from_name(value)
                        .ok_or_else(|| unknown(name, "split", value, SplitName::NAMES))?,
                );
            }
            "task" => {
                self.task = Some(
                    TaskName::from_name(value)
                        .ok_or_else(|| unknown(name, "task", value, TaskName::NAMES))?,
                );
            }
            "variant" => {
                self.variant = Some(
                    VariantName::from_name(value)
                        .ok_or_else(|| unknown(name, "variant", value, VariantName::NAMES))?,
                );
            }
            "lesson" => self.lesson = Some(value.to_owned()),
            "lesson-url" => self.lesson_url = Some(lesson_url(value)?),
            "ray" => self.ray = Some(numbers("ray", value, &[4, 6])?),
            "point" => self.point = Some(numbers("point", value, &[2, 3])?),
            "obbs" => self.obbs = Some(numbers("obbs", value, &[10, 18])?),
            "volumes" => {
                self.volumes = Some(match value {
                    "mesh" => Part3d::Mesh,
                    "brush" => Part3d::Brush,
                    other => return Err(unknown("volumes", "part", other, &["mesh", "brush"])),
                });
            }
            "polygon" => {
                let counts: Vec<usize> = (3..=64).map(|corners| 2 * corners).collect();
                self.polygon = Some(numbers("polygon", value, &counts)?);
            }
            "step" => {
                self.step = Some(value.parse().map_err(|_| {
                    format!(
                        "the address's step \"{}\" is not a whole number",
                        short(value)
                    )
                })?);
            }
            "panels" => self.panels = Some(panels::parse(value)?),
            "lab" => self.lab = Some(value.to_owned()),
            "origin" => self.origins.push(origin(value)?),
            "fresh" => self.fresh = value == "1" || value == "true",
            "debug" => self.debug_panic = value == "panic",
            other => {
                let known: Vec<&str> = PARAMETERS.iter().map(|(n, _)| *n).collect();
                return Err(format!(
                    "the address's parameter \"{}\" is not one the lab reads ({})",
                    short(other),
                    known.join(", ")
                ));
            }
        }
        Ok(())
    }

    /// The `localStorage` key this lab's state is kept under: [`STORAGE_KEY`], followed by
    /// `?lab=NAME` when named, else by the parameters that choose the starting state. So two
    /// labs embedded with different scenes keep their own work, and a lab opened with new
    /// parameters does not come back as an older one.
    pub fn storage_key(&self) -> String {
        if let Some(lab) = &self.lab {
            return format!("{STORAGE_KEY}?lab={lab}");
        }
        let mut parts = Vec::new();
        if let Some(p) = self.preset {
            parts.push(format!("preset={}", p.slug()));
        }
        if let Some(m) = &self.mesh {
            parts.push(format!("mesh={m}"));
        }
        if let Some(s) = self.structure {
            parts.push(format!("structure={}", stored_name(&s)));
        }
        if let Some(s) = self.compare {
            parts.push(format!("compare={}", stored_name(&s)));
        }
        if let Some(split) = self.split {
            parts.push(format!("split={}", stored_name(&split)));
        }
        if let Some(t) = self.task {
            parts.push(format!("task={}", stored_name(&t)));
        }
        for (name, list) in [
            ("ray", &self.ray),
            ("point", &self.point),
            ("obbs", &self.obbs),
            ("polygon", &self.polygon),
        ] {
            if let Some(list) = list {
                let text: Vec<String> = list.iter().map(f32::to_string).collect();
                parts.push(format!("{name}={}", text.join(",")));
            }
        }
        if let Some(v) = self.variant {
            parts.push(format!("variant={}", stored_name(&v)));
        }
        if let Some(part) = self.volumes {
            parts.push(format!("volumes={}", part.word()));
        }
        if let Some(lesson) = &self.lesson {
            parts.push(format!("lesson={lesson}"));
        }
        if let Some(url) = &self.lesson_url {
            parts.push(format!("lesson-url={url}"));
        }
        if let Some(step) = self.step {
            parts.push(format!("step={step}"));
        }
        if parts.is_empty() {
            STORAGE_KEY.to_owned()
        } else {
            format!("{STORAGE_KEY}?{}", parts.join("&"))
        }
    }

    /// The starting state the parameters describe.
    pub fn setup(&self) -> Setup {
        Setup {
            preset: self.preset,
            mesh: self.mesh.clone(),
            structure: self.structure.map(Into::into),
            compare: self.compare.map(Into::into),
            split: self.split.map(Into::into),
            ray: self.ray.clone(),
            point: self.point.clone(),
            obbs: self.obbs.clone(),
            volumes: self.volumes,
            polygon: self.polygon.clone(),
            task: self.task.map(Into::into),
            variant: self.variant.map(Into::into),
            // With a lesson, `step=` is the lesson's step.
            step: if self.lesson.is_some() {
                None
            } else {
                self.step
            },
        }
    }
}

/// A coordinate from a page (address or command), or why the lab cannot take it: it must be
/// finite and within ±[`MAX_COORD`](crate::persist::MAX_COORD), as in scene files.
pub(crate) fn coordinate(what: &str, x: f64) -> Result<f32, String> {
    let max = crate::persist::MAX_COORD;
    if x.is_finite() && x.abs() <= f64::from(max) {
        Ok(x as f32)
    } else {
        Err(format!(
            "{what} has {x}; numbers must be finite and within ±{max:e}"
        ))
    }
}

/// What the address's `parameter` says when its `value` names no `kind` the lab has:
/// `the address's structure: no structure named "kdtree"; try kd-tree, aabb-tree, ...`.
pub(crate) fn unknown(parameter: &str, kind: &str, value: &str, names: &[&str]) -> String {
    format!(
        "the address's {parameter}: {}",
        crate::persist::no_such_name(kind, value, names)
    )
}

/// Comma-separated finite numbers within the lab's range, as many as one of `counts`.
fn numbers(what: &str, value: &str, counts: &[usize]) -> Result<Vec<f32>, String> {
    let list = value
        .split(',')
        .map(|text| {
            let x: f64 = text.trim().parse().map_err(|_| {
                format!(
                    "the address's {what} has \"{}\", which is not a number",
                    short(text)
                )
            })?;
            coordinate(&format!("the address's {what}"), x)
        })
        .collect::<Result<Vec<f32>, String>>()?;
    if counts.contains(&list.len()) {
        Ok(list)
    } else {
        Err(format!(
            "the address's {what} has {} numbers; it takes {}",
            list.len(),
            counts
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(" or ")
        ))
    }
}

/// An origin as browsers write `MessageEvent.origin`: scheme, host and port, no path.
fn origin(value: &str) -> Result<String, String> {
    let value = value.trim_end_matches('/');
    let (scheme, rest) = value.split_once("://").unwrap_or(("", ""));
    let valid = matches!(scheme, "http" | "https")
        && !rest.is_empty()
        && !rest.contains(['/', '?', '#', '@', ' '])
        && rest != "*";
    if valid {
        Ok(value.to_owned())
    } else {
        Err(format!(
            "the address's origin \"{}\" is not an origin like https://course.example.edu (no \
             path, no wildcard)",
            short(value)
        ))
    }
}

/// A `lesson-url=` value: an address on the web (`https://...`, `http://...`) or relative to
/// the lab's page (`lessons/mine.toml`); no other scheme (`data:`, `javascript:`, `file:`).
fn lesson_url(value: &str) -> Result<String, String> {
    let scheme = value
        .split_once(':')
        .map(|(scheme, _)| scheme)
        .filter(|s| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '+'));
    let valid = !value.trim().is_empty()
        && scheme.is_none_or(|s| s.eq_ignore_ascii_case("http") || s.eq_ignore_ascii_case("https"));
    if valid {
        Ok(value.trim().to_owned())
    } else {
        Err(format!(
            "the address's lesson-url \"{}\" is not an http(s) address or a path on this \
             server",
            short(value)
        ))
    }
}

/// Percent-decoding (and `+` as a space), as `URLSearchParams` reads a query; a malformed
/// escape stays as written, and bytes that are not UTF-8 become U+FFFD.
pub fn decode(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' if i + 2 < bytes.len()
                && bytes[i + 1].is_ascii_hexdigit()
                && bytes[i + 2].is_ascii_hexdigit() =>
            {
                let digit = |b: u8| (b as char).to_digit(16).unwrap_or(0) as u8;
                out.push(digit(bytes[i + 1]) * 16 + digit(bytes[i + 2]));
                i += 3;
                continue;
            }
            byte => out.push(byte),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The word the scene format stores for a name (`kd-tree`).
fn stored_name<T: serde::Serialize>(name: &T) -> String {
    match serde_json::to_value(name) {
        Ok(serde_json::Value::String(word)) => word,
        _ => String::new(),
    }
}

/// `text` cut for a message (the scene format's own cut: 40 characters and an ellipsis).
fn short(text: &str) -> std::borrow::Cow<'_, str> {
    crate::persist::shorten(text, 40)
}
