//! `RESULTS.md`: the tables of `results.json` for people (and the README's link).

use std::fmt::Write as _;

use serde_json::Value;

const KINDS: [&str; 4] = ["primary", "shadow", "diffuse", "random"];

fn num(v: &Value, digits: usize) -> String {
    v.as_f64()
        .map_or_else(|| "n/a".into(), |x| format!("{x:.digits$}"))
}

fn kind<'a>(lib: &'a Value, name: &str) -> Option<&'a Value> {
    lib["rays"].as_array()?.iter().find(|k| k["kind"] == name)
}

fn mrays(lib: &Value, name: &str) -> Option<f64> {
    kind(lib, name).and_then(|k| k["mrays_per_s"].as_f64())
}

/// The rate columns of the native tables: each ray kind's first hits, and the shadow rays
/// asked again as occlusion (any hit) where the library has that call.
const RATE_COLUMNS: [&str; 6] = [
    "primary",
    "shadow",
    "shadow as occlusion",
    "diffuse",
    "random",
    "overview",
];

/// Mrays/s of one rate column.
fn rate(lib: &Value, column: &str) -> Option<f64> {
    if column == "shadow as occlusion" {
        kind(lib, "shadow").and_then(|k| k["occluded_mrays_per_s"].as_f64())
    } else {
        mrays(lib, column)
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.2}x", a / b),
        _ => "n/a".into(),
    }
}

fn native_table(md: &mut String, scene: &Value) {
    let _ = writeln!(
        md,
        "| library | build ms | ms/Mtri | SAH | nodes | B/tri | {} | nodes/ray (prim., diff.) | tris/ray (prim., diff.) | closest kq/s | disagreements (rays, closest) |\n{}",
        RATE_COLUMNS.join(" | "),
        "| --- ".repeat(10 + RATE_COLUMNS.len()) + "|"
    );
    for lib in scene["libraries"].as_array().into_iter().flatten() {
        let per = |field: &str| {
            ["primary", "diffuse"]
                .map(|k| kind(lib, k).map_or_else(|| "n/a".into(), |k| num(&k[field], 1)))
                .join(", ")
        };
        let wrong: u64 = lib["rays"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|k| {
                k["disagreements"].as_u64().unwrap_or(0)
                    + k["occlusion_disagreements"].as_u64().unwrap_or(0)
            })
            .sum();
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {wrong}, {} |",
            lib["library"].as_str().unwrap_or_default(),
            num(&lib["build_ms"], 1),
            num(&lib["build_ms_per_mtri"], 0),
            num(&lib["sah_cost"], 1),
            num(&lib["nodes"], 0),
            num(&lib["bytes_per_triangle"], 0),
            RATE_COLUMNS
                .map(|c| rate(lib, c).map_or_else(|| "n/a".into(), |x| format!("{x:.2}")))
                .join(" | "),
            per("nodes_per_ray"),
            per("prims_per_ray"),
            lib["closest_per_s"]
                .as_f64()
                .map_or_else(|| "none".into(), |q| format!("{:.0}", q / 1e3)),
            num(&lib["closest_disagreements"], 0),
        );
    }
}

fn ratio_table(md: &mut String, scene: &Value) {
    let libs: Vec<&Value> = scene["libraries"]
        .as_array()
        .into_iter()
        .flatten()
        .collect();
    let Some((ours, peers)) = libs.split_first() else {
        return;
    };
    let _ = writeln!(
        md,
        "\nbvhlab ÷ peer (above 1 means bvhlab is faster, or its tree cheaper for SAH):\n\n| peer | {} | closest | build speed | SAH cost ratio (peer ÷ ours) |\n{}",
        RATE_COLUMNS.join(" | "),
        "| --- ".repeat(4 + RATE_COLUMNS.len()) + "|"
    );
    for peer in peers {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} |",
            peer["library"].as_str().unwrap_or_default(),
            RATE_COLUMNS
                .map(|c| ratio(rate(ours, c), rate(peer, c)))
                .join(" | "),
            ratio(
                ours["closest_per_s"].as_f64(),
                peer["closest_per_s"].as_f64()
            ),
            ratio(peer["build_ms"].as_f64(), ours["build_ms"].as_f64()),
            ratio(peer["sah_cost"].as_f64(), ours["sah_cost"].as_f64()),
        );
    }
    let _ = writeln!(
        md,
        "\nbvhlab's occlusion walk ÷ its first-hit walk, on the same shadow rays: {}.",
        ratio(rate(ours, "shadow as occlusion"), rate(ours, "shadow"))
    );
}

/// A WebAssembly library of a scene, found by the start of its name (`bvhlab`,
/// `three-mesh-bvh`, `rapier`): older `wasm.json` files have no other key.
fn wasm_lib<'a>(scene: &'a Value, prefix: &str) -> Option<&'a Value> {
    scene["libraries"]
        .as_array()?
        .iter()
        .find(|l| l["library"].as_str().is_some_and(|n| n.starts_with(prefix)))
}

/// The ray kinds of the WebAssembly run, in its order: `wasm.json` lists them (the wasm
/// module reports them), older files did not and had the native four.
fn wasm_kinds(wasm: &Value) -> Vec<String> {
    wasm["kinds"].as_array().map_or_else(
        || KINDS.map(str::to_owned).to_vec(),
        |kinds| {
            kinds
                .iter()
                .filter_map(|k| k.as_str().map(str::to_owned))
                .collect()
        },
    )
}

/// The "| --- |" line under a header of `columns` columns.
fn rule(columns: usize) -> String {
    "| --- ".repeat(columns) + "|"
}

fn wasm_section(md: &mut String, all: &Value) {
    let wasm = &all["wasm"];
    if wasm.is_null() {
        md.push_str("\n## WebAssembly\n\nNot measured in this run (`compare.sh` measures it).\n");
        return;
    }
    let (rapier, rapier_how) = wasm["rapier"].as_str().map_or_else(Default::default, |v| {
        (
            format!(
                ", @dimforge/rapier3d-compat {v} (parry3d {})",
                wasm["parry"].as_str().unwrap_or("?")
            ),
            " and parry3d inside rapier's published module (one trimesh collider in a `World`, asked with `Collider.castRay`, `Collider.intersectsRay` (the occlusion column) and `Collider.projectPoint`, each call crossing the JS-wasm boundary as a rapier user's does)",
        )
    });
    let clock = if wasm["clock"] == "cpu" {
        " Timed on node's CPU time (`run.mjs --clock cpu`), not the wall clock."
    } else {
        ""
    };
    let _ = writeln!(
        md,
        "\n## WebAssembly (node {}, three {}, three-mesh-bvh {}{rapier})\n\nbvhlab built for `wasm32-unknown-unknown` with `+simd128` (release), three-mesh-bvh with the SAH strategy{rapier_how}, in the same node process, on the same triangles, rays and points (generated by the same workload code inside the wasm module). Mrays/s; closest point in thousands of queries/s.{clock}\n",
        wasm["node"].as_str().unwrap_or("?"),
        wasm["three"].as_str().unwrap_or("?"),
        wasm["three_mesh_bvh"].as_str().unwrap_or("?"),
    );
    let kinds = wasm_kinds(wasm);
    wasm_rates_table(md, all, &kinds);
    wasm_ratio_table(md, wasm, &kinds);
}

/// A row per library per scene: its rates, its disagreements with bvhlab, and how it fares
/// against its own native build (bvhlab's against native bvhlab, rapier's against native
/// parry3d).
fn wasm_rates_table(md: &mut String, all: &Value, kinds: &[String]) {
    let _ = writeln!(
        md,
        "| scene | library | build ms | {} | closest kq/s | disagreements (rays, closest) | wasm ÷ native (primary, random, closest) |\n{}",
        kinds.join(" | "),
        rule(kinds.len() + 6)
    );
    for scene in all["wasm"]["scenes"].as_array().into_iter().flatten() {
        let native_libs: Vec<&Value> = all["native"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|s| s["scene"] == scene["scene"])
            .flat_map(|s| s["libraries"].as_array().into_iter().flatten())
            .collect();
        for lib in scene["libraries"].as_array().into_iter().flatten() {
            let get = |k: &str| lib["mrays"][k].as_f64();
            let wrong: u64 = kinds
                .iter()
                .filter_map(|k| lib["disagreements"][k].as_u64())
                .sum();
            let name = lib["library"].as_str().unwrap_or_default();
            // bvhlab's native row is the first (the 4-wide tree, as here).
            let native = if lib["is_bvhlab"].as_bool() == Some(true) {
                native_libs.first().copied()
            } else if name.starts_with("rapier") {
                native_libs.iter().copied().find(|n| {
                    n["library"]
                        .as_str()
                        .is_some_and(|n| n.starts_with("parry3d"))
                })
            } else {
                None
            };
            let vs_native = native.map_or_else(String::new, |n| {
                format!(
                    "{}, {}, {}",
                    ratio(get("primary"), mrays(n, "primary")),
                    ratio(get("random"), mrays(n, "random")),
                    ratio(lib["closest_per_s"].as_f64(), n["closest_per_s"].as_f64())
                )
            });
            let _ = writeln!(
                md,
                "| {} | {name} | {} | {} | {} | {wrong}, {} | {vs_native} |",
                scene["scene"].as_str().unwrap_or_default(),
                num(&lib["build_ms"], 1),
                kinds
                    .iter()
                    .map(|k| get(k).map_or_else(|| "n/a".into(), |x| format!("{x:.2}")))
                    .collect::<Vec<_>>()
                    .join(" | "),
                lib["closest_per_s"]
                    .as_f64()
                    .map_or_else(|| "n/a".into(), |q| format!("{:.0}", q / 1e3)),
                num(&lib["closest_disagreements"], 0),
            );
        }
    }
}

/// Above this share of rapier's time spent in the per-call overhead, the rate less the
/// overhead is marked as noisy (it is then a small difference of two large times).
const NOISY_SHARE: f64 = 0.75;

/// bvhlab ÷ each peer per scene (issue 19's goals: 5x three-mesh-bvh; 5x rapier as called,
/// 2x with rapier's per-call overhead subtracted), and that overhead itself.
fn wasm_ratio_table(md: &mut String, wasm: &Value, kinds: &[String]) {
    let _ = writeln!(
        md,
        "\nbvhlab ÷ peer (above 1 means bvhlab is faster; issue 19 asks for 5x three-mesh-bvh, 5x rapier as called and 2x rapier less its per-call overhead). rapier's per-call overhead is the time of the same calls on a one-triangle collider (the JS loop, the boundary crossing and the `RawVector` each vector argument allocates and frees, and a query next to free), subtracted as time − calls × overhead. †: the overhead is over three quarters of rapier's time there, so what is left is a small difference of two large times and carries both their noise.\n\n| scene | ratio | build | {} | closest |\n{}",
        kinds.join(" | "),
        rule(kinds.len() + 4)
    );
    for scene in wasm["scenes"].as_array().into_iter().flatten() {
        let Some(ours) = wasm_lib(scene, "bvhlab") else {
            continue;
        };
        let name = scene["scene"].as_str().unwrap_or_default();
        let mut row = |label: &str, build: String, per: &dyn Fn(&str) -> String| {
            let cells: Vec<String> = kinds.iter().map(|k| per(k)).collect();
            let _ = writeln!(
                md,
                "| {name} | {label} | {build} | {} | {} |",
                cells.join(" | "),
                per("closest")
            );
        };
        // The closest point's rate sits beside the kinds' under its own keys.
        let rate_of = |lib: &Value, rays: &str, closest: &str, k: &str| {
            if k == "closest" {
                lib[closest].as_f64()
            } else {
                lib[rays][k].as_f64()
            }
        };
        if let Some(three) = wasm_lib(scene, "three-mesh-bvh") {
            row(
                "bvhlab ÷ three-mesh-bvh",
                ratio(three["build_ms"].as_f64(), ours["build_ms"].as_f64()),
                &|k| {
                    ratio(
                        rate_of(ours, "mrays", "closest_per_s", k),
                        rate_of(three, "mrays", "closest_per_s", k),
                    )
                },
            );
        }
        let Some(rapier) = wasm_lib(scene, "rapier") else {
            continue;
        };
        row(
            "bvhlab ÷ rapier, as called",
            ratio(rapier["build_ms"].as_f64(), ours["build_ms"].as_f64()),
            &|k| {
                ratio(
                    rate_of(ours, "mrays", "closest_per_s", k),
                    rate_of(rapier, "mrays", "closest_per_s", k),
                )
            },
        );
        row(
            "bvhlab ÷ rapier, less its per-call overhead",
            String::new(),
            &|k| {
                let cell = ratio(
                    rate_of(ours, "mrays", "closest_per_s", k),
                    rate_of(rapier, "mrays_net", "closest_per_s_net", k),
                );
                // The overhead's share of rapier's time: calls/s × seconds per call.
                let share = rate_of(rapier, "mrays", "closest_per_s", k)
                    .zip(rapier["overhead_us"][k].as_f64())
                    .map(|(rate, us)| {
                        if k == "closest" {
                            rate * us * 1e-6
                        } else {
                            rate * us
                        }
                    });
                if share.is_some_and(|s| s > NOISY_SHARE) {
                    cell + " †"
                } else {
                    cell
                }
            },
        );
        row("rapier's per-call overhead, µs", String::new(), &|k| {
            num(&rapier["overhead_us"][k], 2)
        });
    }
}

fn parallel_section(md: &mut String, all: &Value) {
    let par = &all["parallel"];
    let Some(scenes) = par["scenes"].as_array() else {
        md.push_str("\n## Both cores\n\nNot in this run: `compare.sh` measures it with the default build, unpinned, after the single-threaded run, into `bench/RESULTS.md`.\n");
        return;
    };
    let _ = writeln!(
        md,
        "\n## Both cores (bvhlab's `parallel` feature, {} cores, unpinned, {})\n\nThe batch calls (`ray_first_hits`, `ray_any_hits`, `closest_points`; closest points answered in Morton order) and the build, in a rayon pool of one thread and of every core, on the same workload (a shadow ray's limit is put in its direction, so the batch takes one limit). Queries (triangles for the build) per second, in millions; the speed-up is every core ÷ one thread. \"same\": both pools gave the same answers (the same tree for the build).\n\n| scene | what | one thread | every core | speed-up | same |\n{}",
        par["cores"],
        par["date"].as_str().unwrap_or_default(),
        "| --- ".repeat(6) + "|"
    );
    for scene in scenes {
        for row in scene["rows"].as_array().into_iter().flatten() {
            let per_s = |k: &str| {
                row[k]
                    .as_f64()
                    .map_or_else(|| "n/a".into(), |x| format!("{:.2}", x / 1e6))
            };
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {} |",
                scene["scene"].as_str().unwrap_or_default(),
                row["what"].as_str().unwrap_or_default(),
                per_s("one_thread_per_s"),
                per_s("all_cores_per_s"),
                row["speedup"]
                    .as_f64()
                    .map_or_else(|| "n/a".into(), |x| format!("{x:.2}x")),
                if row["same_answers"].as_bool() == Some(true) {
                    "yes"
                } else {
                    "NO"
                },
            );
        }
    }
}

fn disagreements(md: &mut String, all: &Value) {
    md.push_str("\n## Disagreements with bvhlab\n\nA ray disagrees when one library hits and the other misses, or both hit with `t` more than 1e-5 apart relative; a closest point when the distances differ by more than 1e-5 relative. bvhlab's answers equal brute force's (its tests check that), so each line is the peer's. Up to five examples each: (index, bvhlab, peer).\n\n");
    let mut any = false;
    for scene in all["native"].as_array().into_iter().flatten() {
        for lib in scene["libraries"].as_array().into_iter().flatten() {
            for k in lib["rays"].as_array().into_iter().flatten() {
                let n = k["disagreements"].as_u64().unwrap_or(0);
                if n > 0 {
                    any = true;
                    let rays = k["rays"].as_f64().unwrap_or(1.0);
                    let _ = writeln!(
                        md,
                        "- {} on {}, {} rays: {n} of {rays} ({:.3}%), of which {} missed hits; e.g. {}",
                        lib["library"].as_str().unwrap_or_default(),
                        scene["scene"].as_str().unwrap_or_default(),
                        k["kind"].as_str().unwrap_or_default(),
                        n as f64 / rays * 100.0,
                        k["missed"],
                        k["examples"]
                    );
                }
                let occlusion = k["occlusion_disagreements"].as_u64().unwrap_or(0);
                if occlusion > 0 {
                    any = true;
                    let _ = writeln!(
                        md,
                        "- {} on {}, {} rays asked as occlusion: {occlusion} verdicts differ from bvhlab's first hit",
                        lib["library"].as_str().unwrap_or_default(),
                        scene["scene"].as_str().unwrap_or_default(),
                        k["kind"].as_str().unwrap_or_default(),
                    );
                }
            }
            if lib["closest_disagreements"].as_u64().is_some_and(|n| n > 0) {
                any = true;
                let _ = writeln!(
                    md,
                    "- {} on {}, closest point: {}; e.g. {}",
                    lib["library"].as_str().unwrap_or_default(),
                    scene["scene"].as_str().unwrap_or_default(),
                    lib["closest_disagreements"],
                    lib["closest_examples"]
                );
            }
        }
    }
    if !any {
        md.push_str("None.\n");
    }
}

/// The Markdown report of a run (`all` is what `results.json` holds).
pub fn markdown(all: &Value) -> String {
    let m = &all["machine"];
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# bvhlab against peer libraries\n\nMeasured by `bash crates/bvhlab-bench/compare.sh` ({} mode) on {} ({} cores, this run pinned to CPU {}), {}, {}, RUSTFLAGS=`{}`, {}. Single thread, median of {} runs. Regenerate with the same command; `results.json` beside this file has every number.\n",
        all["mode"].as_str().unwrap_or_default(),
        m["cpu"].as_str().unwrap_or_default(),
        m["cores"],
        m["cpus_allowed"].as_str().unwrap_or_default(),
        m["rustc"].as_str().unwrap_or_default(),
        m["profile"].as_str().unwrap_or_default(),
        m["rustflags"].as_str().unwrap_or_default(),
        m["date"].as_str().unwrap_or_default(),
        all["repeats"],
    );
    let w = &all["workload"];
    let _ = writeln!(
        md,
        "Workload (`crates/bvhlab-bench/src/workload.rs`): primary rays of a {}x{} pinhole camera from {} viewpoints (coherent); shadow rays from the primary hits to one point light; cosine-weighted diffuse bounces from the primary hits (incoherent); {} random rays in the bounding box (the issue's \"incoherent\"); overview: one more {}x{} camera {} bounding radii away, so that the mesh is small in the frame and most rays miss it; {} closest-point queries at random points in the box grown 1.5x. Mrays/s per kind; \"shadow as occlusion\": the shadow rays asked with the library's own occlusion call where it has one (bvhlab `ray_any_hit`, obvhs `ray_traverse_miss`, parry3d `intersects_local_ray`, Embree `rtcOccluded1`; tinybvh-rs 0.1.0-beta.3 does not bind tinybvh's `IsOccluded`, bvh 0.13 has no such call). Nodes and triangles tested per ray where the library reports them (tinybvh: its traversal steps). SAH cost: `C_trav = C_tri = 1`, surface areas relative to the root, computed here from each library's nodes (bvh, obvhs, parry3d and tinybvh's binary BVH expose them; BVH8_CPU and Embree do not). B/tri: the bytes of nodes, indices and the library's copy of the triangles, per triangle.\n\nLibraries: bvhlab's `Bvh4` (`Bvh4::build`: the binned-SAH `AabbTree3` that costs leaves by blocks of four triangles, leaves of up to 16, collapsed 4-wide, its triangles in blocks tested four at a time; `ray_first_hit`, `ray_any_hit`, `closest_point`; build time includes the collapse; nodes are wide nodes; \"ours\" in the ratio tables) and the binary `AabbTree3` itself (`SpatialIndex::ray_first_hit`, `closest_point`); obvhs 0.4 `Bvh2` (PLOC, `medium_build`); parry3d 0.31 `TriMesh` (`cast_local_ray`, `project_local_point`); bvh 0.13 (SAH, `nearest_traverse_iterator` with a two-sided Möller-Trumbore, `nearest_to`); tinybvh through tinybvh-rs 0.1.0-beta.3 (`BVH::new`, C++ always built with `-march=native`; `BVH8_CPU` only when the Rust side has AVX2, i.e. with `-C target-cpu=native`); Intel Embree 3, the system's `libembree3` through the `embree` crate 0.3.8 (only with the bench crate's `embree` feature, which `compare.sh` turns on when the library is installed or it can install it), as a user gets it: default scene flags and build quality (medium: binned SAH without spatial splits; with AVX, a `BVH8<triangle4>`), kernels picked at run time (SSE to AVX-512), one build thread (`threads=1`), build time from `rtcNewScene` to `rtcCommitScene` including the copy of the mesh into Embree's buffers; `rtcIntersect1`, `rtcOccluded1`, and `rtcPointQuery` with bvhlab's point-triangle projection in its callback; B/tri from Embree's memory monitor (its buffers and the BVH, which keeps its own copy of the triangles); its nodes are not exposed.\n",
        w["camera"][0],
        w["camera"][1],
        w["viewpoints"],
        w["random_rays"],
        w["camera"][0],
        w["camera"][1],
        bvhlab_bench::workload::OVERVIEW_DISTANCE,
        w["points"],
    );
    for scene in all["native"].as_array().into_iter().flatten() {
        let _ = writeln!(
            md,
            "\n## {} ({} triangles)\n",
            scene["scene"].as_str().unwrap_or_default(),
            scene["triangles"]
        );
        native_table(&mut md, scene);
        ratio_table(&mut md, scene);
    }
    wasm_section(&mut md, all);
    parallel_section(&mut md, all);
    disagreements(&mut md, all);
    md
}
