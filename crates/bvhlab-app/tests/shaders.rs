//! Every WGSL shader in the app's sources, found by walking `src/` when the tests run (so
//! shaders added later are covered without a list to update), parsed and validated with naga,
//! the compiler wgpu itself uses. Failures read as naga's own messages, with the file name and
//! line. Shaders without compute entry points are also translated to GLSL ES 3.00 for WebGL2,
//! the web's fallback, which has no storage buffers, so one written for WebGPU only fails here.
//! The heat map's tree structs are checked against the core's GPU layout they mirror.

use std::path::{Path, PathBuf};

use naga::back::glsl;
use naga::valid::{Capabilities, ValidationFlags, Validator};

/// What every target offers: WebGL2 (the web's fallback) grants no optional capability, so a
/// shader that needs one (64-bit floats, subgroups, cube-map arrays...) fails here rather than
/// on a student's browser.
const TARGET_CAPABILITIES: Capabilities = Capabilities::empty();

fn source_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.wgsl` file under `dir`, sorted.
fn wgsl_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        let entries = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()));
        for entry in entries {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "wgsl") {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// Parses and validates `source`; the error is naga's report, naming `name` and the line.
fn check(name: &str, source: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    let module = naga::front::wgsl::parse_str(source)
        .map_err(|e| e.emit_to_string_with_path(source, name))?;
    let info = Validator::new(ValidationFlags::all(), TARGET_CAPABILITIES)
        .validate(&module)
        .map_err(|e| e.emit_to_string_with_path(source, name))?;
    Ok((module, info))
}

/// Translates every entry point to GLSL ES 3.00 as WebGL2 runs it; the first failure as text.
fn check_webgl2(
    name: &str,
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
) -> Result<(), String> {
    let options = glsl::Options {
        version: glsl::Version::Embedded {
            version: 300,
            is_webgl: true,
        },
        ..glsl::Options::default()
    };
    for entry in &module.entry_points {
        let pipeline = glsl::PipelineOptions {
            shader_stage: entry.stage,
            entry_point: entry.name.clone(),
            multiview: None,
        };
        let mut out = String::new();
        glsl::Writer::new(
            &mut out,
            module,
            info,
            &options,
            &pipeline,
            naga::proc::BoundsCheckPolicies::default(),
        )
        .and_then(|mut writer| writer.write())
        .map_err(|e| format!("{name}: entry point `{}` for WebGL2: {e}", entry.name))?;
    }
    Ok(())
}

/// Shaders the app assembles from parts (WGSL has no `#include`): their name, the source the
/// app really compiles, and the files it is made of. Those files are checked through it.
fn assembled() -> Vec<(&'static str, String, [&'static str; 2])> {
    use bvhlab_app::render3d::heatmap::gpu::{colorize_shader_source, trace_shader_source};
    vec![
        (
            "render3d/heatmap (trace)",
            trace_shader_source(),
            ["params.wgsl", "trace.wgsl"],
        ),
        (
            "render3d/heatmap (colorize)",
            colorize_shader_source(),
            ["params.wgsl", "colorize.wgsl"],
        ),
    ]
}

/// The parts of assembled shaders: `exact.wgsl` is a library the trace pass includes.
const LIBRARY_PARTS: [&str; 1] = ["exact.wgsl"];

#[test]
fn every_shader_parses_and_validates() {
    let root = source_dir();
    let files = wgsl_files(&root);
    let mut failures = Vec::new();
    let assembled = assembled();
    let mut sources = Vec::new();
    for path in &files {
        let name = path
            .strip_prefix(&root)
            .unwrap_or(path)
            .display()
            .to_string();
        let file = path.file_name().and_then(|f| f.to_str()).unwrap_or("");
        let part = name.starts_with("render3d/heatmap")
            && (LIBRARY_PARTS.contains(&file) || assembled.iter().any(|a| a.2.contains(&file)));
        if part {
            continue;
        }
        sources.push((
            name,
            std::fs::read_to_string(path).expect("a readable shader"),
        ));
    }
    sources.extend(
        assembled
            .into_iter()
            .map(|(name, source, _)| (name.to_owned(), source)),
    );
    for (name, source) in &sources {
        let (name, source) = (name.as_str(), source.as_str());
        match check(name, source) {
            Ok((module, info)) => {
                let compute = module
                    .entry_points
                    .iter()
                    .any(|e| e.stage == naga::ShaderStage::Compute);
                if !compute && let Err(error) = check_webgl2(name, &module, &info) {
                    failures.push(error);
                }
            }
            Err(report) => failures.push(report),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // The 3D view's renderer's own shaders at least (others may add more).
    let names = files
        .iter()
        .filter_map(|p| p.file_name()?.to_str())
        .collect::<Vec<_>>();
    for expected in [
        "mesh.wgsl",
        "lines.wgsl",
        "triangles.wgsl",
        "markers.wgsl",
        "blit.wgsl",
    ] {
        assert!(
            names.contains(&expected),
            "{expected} not found in {names:?}"
        );
    }
}

/// The size of a struct's field, from a function that borrows it (`|n: &Node| &n.min`).
fn field_size<T, F>(_: fn(&T) -> &F) -> u32 {
    size_of::<F>() as u32
}

/// A Rust struct's size and its fields' names, offsets and sizes, in declaration order.
macro_rules! rust_layout {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        (
            size_of::<$ty>() as u32,
            vec![$((
                stringify!($field).to_owned(),
                std::mem::offset_of!($ty, $field) as u32,
                field_size(|v: &$ty| &v.$field),
            )),*],
        )
    };
}

/// The size of struct `name` in `module` and its members' names, offsets and sizes, as naga
/// lays them out.
fn wgsl_layout(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32, u32)>) {
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("the types lay out");
    module
        .types
        .iter()
        .find_map(|(_, ty)| match &ty.inner {
            naga::TypeInner::Struct { members, span } if ty.name.as_deref() == Some(name) => {
                let members = members
                    .iter()
                    .map(|m| {
                        let member = m.name.clone().unwrap_or_default();
                        (member, m.offset, layouter[m.ty].size)
                    })
                    .collect();
                Some((*span, members))
            }
            _ => None,
        })
        .unwrap_or_else(|| panic!("struct {name} is declared"))
}

/// The value of the `u32` constant `name` in `module`.
fn wgsl_u32_constant(module: &naga::Module, name: &str) -> u32 {
    let constant = module
        .constants
        .iter()
        .find_map(|(_, c)| (c.name.as_deref() == Some(name)).then_some(c))
        .unwrap_or_else(|| panic!("constant {name} is declared"));
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::U32(value)) => value,
        ref other => panic!("{name} is not a u32 literal: {other:?}"),
    }
}

/// The heat map's shader reads the core's AABB tree as the core lays it out for the GPU
/// (`bvhlab::structure::bvh::layout::gpu`): the same fields at the same offsets with the same
/// sizes, structs of the same size, and a stack as deep as the core's walk needs. A change on
/// either side without the other fails here.
#[test]
fn the_gpu_tree_layout_is_the_wgsl_layout() {
    use bvhlab::structure::bvh::MAX_DEPTH;
    use bvhlab::structure::bvh::layout::gpu::{GpuNode, GpuTriangle};
    use bvhlab_app::render3d::heatmap::gpu::trace_shader_source;

    let source = trace_shader_source();
    let module = naga::front::wgsl::parse_str(&source).expect("valid WGSL");
    assert_eq!(
        wgsl_layout(&module, "Node"),
        rust_layout!(GpuNode {
            min,
            start,
            max,
            count
        }),
        "trace.wgsl's Node against the core's GpuNode"
    );
    assert_eq!(
        wgsl_layout(&module, "Tri"),
        rust_layout!(GpuTriangle {
            a,
            id,
            b,
            flags,
            c,
            pad
        }),
        "trace.wgsl's Tri against the core's GpuTriangle"
    );
    assert_eq!(
        wgsl_u32_constant(&module, "STACK") as usize,
        MAX_DEPTH + 2,
        "trace.wgsl's STACK against the core's stack capacity"
    );
}

#[test]
fn a_syntax_error_is_reported_with_its_file_and_line() {
    let source = "@vertex\nfn main() -> @builtin(position) vec4<f32> {\n    let x = 1.0\n    var y = 2.0;\n    return vec4<f32>(x);\n}\n";
    let report = check("broken.wgsl", source).expect_err("a missing `;`");
    // The `;` missing at the end of line 3 is noticed at the next token, `var` on line 4.
    assert!(report.contains("broken.wgsl:4"), "{report}");
    assert!(report.contains("expected"), "{report}");
}

#[test]
fn a_type_error_is_reported_with_its_file_and_line() {
    // Parses, but returns a scalar where the signature promises a vector: the validator's
    // error, not the parser's.
    let source = "@vertex\nfn main() -> @builtin(position) vec4<f32> {\n    let v = vec4<f32>(1.0);\n    return v.x;\n}\n";
    let report = check("typed.wgsl", source).expect_err("a scalar returned as a vector");
    assert!(report.contains("typed.wgsl:4"), "{report}");
}

#[test]
fn a_storage_buffer_in_a_render_shader_fails_the_webgl2_check() {
    let source = "@group(0) @binding(0) var<storage, read> data: array<vec4<f32>>;\n\
                  @vertex\nfn main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {\n\
                  return data[i];\n}\n";
    let (module, info) = check("storage.wgsl", source).expect("valid WGSL");
    let error = check_webgl2("storage.wgsl", &module, &info).expect_err("no SSBOs in ES 3.00");
    assert!(error.contains("storage.wgsl"), "{error}");
}
