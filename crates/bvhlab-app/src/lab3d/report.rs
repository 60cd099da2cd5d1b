//! The 3D view's part of the lab's report (the browser test reads it).

use serde::Serialize;

use super::Lab3d;
use crate::recording::Answer;

/// The 3D view's state in brief.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Report3d {
    /// The mesh's name, once loaded.
    pub mesh: Option<String>,
    /// Its triangles.
    pub triangles: usize,
    /// The structure.
    pub structure: String,
    /// A build under way: how far it is, 0 to 1.
    pub building: Option<f32>,
    /// How long the finished build took, in milliseconds.
    pub build_ms: Option<f64>,
    /// The view's area on the page, in points: `[x0, y0, x1, y1]`.
    pub view: [f32; 4],
    /// The ray: origin and direction.
    pub ray: Option<[f32; 6]>,
    /// The first hit: triangle, t, point.
    pub hit: Option<Hit3dReport>,
    /// The query point.
    pub point: Option<[f32; 3]>,
    /// Whether the recorded answer equals brute force's.
    pub agrees: Option<bool>,
    /// The recorded query's nodes, bound tests and triangle tests.
    pub cost: Option<[u64; 3]>,
    /// Brute force's triangle tests.
    pub brute_force_tests: Option<u64>,
    /// The last message (a refused file, a structure not offered for this size).
    pub message: Option<String>,
    /// The heat map, when shown: "gpu" or "cpu", its progress and its largest count.
    pub heat_map: Option<HeatReport>,
}

/// A first hit in 3D.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Hit3dReport {
    /// The triangle's index.
    pub triangle: usize,
    /// The ray parameter.
    pub t: f32,
    /// The hit point.
    pub point: [f32; 3],
}

/// The heat map's state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HeatReport {
    /// Where it is computed: "gpu" or "cpu".
    pub device: String,
    /// How far it is, 0 to 1.
    pub progress: f32,
    /// The largest count in the image.
    pub max: u32,
}

impl Report3d {
    /// The report of the 3D view's state.
    pub fn of(lab: &Lab3d) -> Self {
        let rec = lab.recorded();
        let hit = rec.and_then(|r| match (&r.answer, r.question.ray) {
            (Answer::Hit(Some(h)), Some(ray)) => Some(Hit3dReport {
                triangle: h.prim,
                t: h.t,
                point: ray.at(h.t).to_array(),
            }),
            _ => None,
        });
        Self {
            mesh: lab.mesh.as_ref().map(|m| m.name.clone()),
            triangles: lab
                .mesh
                .as_ref()
                .map_or(0, super::mesh::Mesh3d::triangle_count),
            structure: lab.settings.kind.label_in(3).to_owned(),
            building: lab.job.as_ref().map(super::build::BuildJob::fraction),
            build_ms: lab.built.as_ref().map(|b| b.build_ms),
            view: [
                lab.view_rect.min.x,
                lab.view_rect.min.y,
                lab.view_rect.max.x,
                lab.view_rect.max.y,
            ],
            ray: lab.ray.map(|r| {
                let (o, d) = (r.origin(), r.dir());
                [o.x, o.y, o.z, d.x, d.y, d.z]
            }),
            hit,
            point: lab.point.map(|p| p.to_array()),
            agrees: rec.map(crate::recording::Recording::agrees),
            cost: rec.map(|r| [r.cost.nodes_visited, r.cost.bound_tests, r.cost.prim_tests]),
            brute_force_tests: rec.map(|r| r.brute_cost.prim_tests),
            message: lab.message.clone(),
            heat_map: lab.heat_report(),
        }
    }
}
