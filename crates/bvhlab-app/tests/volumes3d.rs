//! Lecture §2 in 3D (issue 32, part 1): the bounding volumes of the whole mesh and of a
//! brushed part, checked against the core's own fits of the same vertices, the part against
//! the core's range query, and the slab test with three slabs and its failure cases; driven
//! through the panel and the model's actions, as a student drives them.

use std::collections::BTreeSet;

use bvhlab::glam::Vec3;
use bvhlab::structure::RangeShape;
use bvhlab::{
    Aabb3, BruteForce, ConvexHull3, FitKind, FitReport, Obb3, SpatialIndex, SpatialQuery, Sphere3,
    Triangle3,
};
use bvhlab_app::LabApp;
use bvhlab_app::model::tools::Tool3d;
use bvhlab_app::model::volumes3d::Part3d;
use bvhlab_app::model::{Action3d, HalfAction};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};

use crate::common::{act, click, labels, settle, shows};
use crate::view3d::{lab_3d, three};

/// The distinct vertices of `triangles` of the mesh shown, in the mesh's order, found
/// here from the index triples (not by the lab's own code).
fn vertices_of(h: &Harness<'_, LabApp>, triangles: &BTreeSet<usize>) -> Vec<Vec3> {
    let mesh = &three(h).mesh.as_ref().expect("a mesh").mesh;
    let used: BTreeSet<u32> = triangles.iter().flat_map(|&t| mesh.indices()[t]).collect();
    used.iter().map(|&v| mesh.positions()[v as usize]).collect()
}

/// The lab's fits, checked bit for bit against the core's fits of `expected` vertices.
fn assert_fits_are_the_cores(h: &Harness<'_, LabApp>, expected: &[Vec3]) {
    let part = three(h).part_fits().expect("the volumes are shown");
    assert_eq!(part.vertices, expected.len());
    let fits = part.fits.as_ref().expect("fits of a non-empty part");
    assert_eq!(fits.aabb, Aabb3::from_points(expected));
    assert_eq!(fits.centroid, Sphere3::centroid_fit(expected));
    assert_eq!(fits.ritter, Sphere3::ritter_fit(expected));
    assert_eq!(fits.welzl, Sphere3::welzl_fit(expected));
    assert_eq!(fits.obb, Obb3::pca_fit(expected));
    assert_eq!(
        fits.hull.vertices().len(),
        ConvexHull3::from_points(expected).vertices().len()
    );
    let report = FitReport::for_points(expected);
    for kind in FitKind::ALL {
        let (ours, core) = (fits.report.get(kind), report.get(kind));
        assert_eq!(ours.map(|m| m.measure), core.map(|m| m.measure), "{kind:?}");
        // What the table says: the volume with three decimals.
        let shown = format!("{:.3}", core.expect("measured").measure);
        assert!(shows(h, &shown), "{kind:?}: {shown} not in the table");
    }
    // Every vertex lies in every volume (within rounding): they bound the part.
    let size = fits.aabb.max - fits.aabb.min;
    let slack = 1e-4 * size.max_element();
    for p in expected {
        for s in [&fits.centroid, &fits.ritter, &fits.welzl] {
            assert!(s.center.distance(*p) <= s.radius + slack);
        }
        let local = fits.obb.to_local(*p);
        assert!((local.abs() - fits.obb.half_extents).max_element() <= slack);
    }
}

#[test]
fn the_volumes_of_the_mesh_and_of_a_brushed_part_are_the_cores_fits() {
    let mut h = lab_3d();
    assert!(three(&h).part_fits().is_none(), "off until asked for");
    assert!(three(&h).display.structure && three(&h).display.marks);
    click(&mut h, "Show the bounding volumes");
    settle(&mut h);
    // §2 comes before the trees: their nodes and marks are put away, and come back after.
    assert!(!three(&h).display.structure && !three(&h).display.marks);
    assert!(shows(&h, "surface area"), "the 3D table's sizes");
    let all: BTreeSet<usize> = (0..three(&h).triangles().len()).collect();
    assert_eq!(
        three(&h).part_fits().expect("shown").triangles.len(),
        all.len()
    );
    assert_fits_are_the_cores(&h, &vertices_of(&h, &all));

    // The brush: the Point tool comes with it, and its part is the core's range answer.
    click(&mut h, "the brush (triangles within r of q)");
    settle(&mut h);
    assert_eq!(three(&h).tool, Tool3d::Point);
    assert_eq!(three(&h).volumes.part, Part3d::Brush);
    // The point the lab opens with lies beside the mesh: the brush starts at its closest
    // point on the mesh, so it holds triangles at once.
    let q = three(&h).point.expect("a point");
    let on_mesh = three(&h)
        .triangles()
        .iter()
        .map(|t| t.project_point(q).distance(q))
        .fold(f32::INFINITY, f32::min);
    assert!(on_mesh < 1e-4, "q is {on_mesh} off the mesh");
    assert!(!three(&h).part_fits().expect("shown").triangles.is_empty());
    let mesh_size = three(&h).mesh.as_ref().expect("mesh").size();
    let triangles: Vec<Triangle3> = three(&h).triangles().to_vec();
    let brute = BruteForce::build(&triangles);
    for (vertex, radius) in [(0, 0.1), (triangles.len() / 2, 0.2), (17, 0.05)] {
        let q = triangles[vertex].a + Vec3::splat(mesh_size * 0.01);
        let radius = mesh_size * radius;
        act(&mut h, Action3d::SetPoint(Some(q)));
        act(&mut h, HalfAction::SetRadius(radius));
        settle(&mut h);
        let expected: BTreeSet<usize> = brute
            .range(&RangeShape::Ball(Sphere3 { center: q, radius }))
            .into_iter()
            .collect();
        assert!(!expected.is_empty() && expected.len() < triangles.len());
        let part = three(&h).part_fits().expect("shown");
        let got: BTreeSet<usize> = part.triangles.iter().map(|&t| t as usize).collect();
        assert_eq!(got, expected, "the brush at {q} with r = {radius}");
        assert_fits_are_the_cores(&h, &vertices_of(&h, &expected));
        // The part is lit in the view, and named in the legend.
        let lit: BTreeSet<usize> = h.state().ui.view3d.drawn[0]
            .highlights
            .iter()
            .map(|&(t, _)| t as usize)
            .collect();
        assert!(expected.is_subset(&lit));
        assert!(labels(&h).iter().any(|l| l.contains("brushed triangles")));
    }
    // Off the mesh: an empty part says so and fits nothing.
    act(
        &mut h,
        Action3d::SetPoint(Some(Vec3::splat(mesh_size * 50.0))),
    );
    settle(&mut h);
    assert!(three(&h).part_fits().expect("shown").fits.is_none());
    assert!(shows(&h, "No triangle lies within r of q"));
    click(&mut h, "Show the bounding volumes");
    settle(&mut h);
    assert!(three(&h).part_fits().is_none());
    assert!(three(&h).display.structure && three(&h).display.marks);
}

#[test]
fn the_slab_test_has_three_slabs_and_the_naive_formula_fails_on_a_slab_plane() {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    settle(&mut h);
    let aabb = three(&h)
        .part_fits()
        .expect("shown")
        .fits
        .as_ref()
        .expect("fits")
        .aabb;
    // A ray through the box's middle, on a slant.
    let origin = aabb.center() - (aabb.max - aabb.min) * Vec3::new(1.5, 1.0, 0.7);
    let ray = bvhlab::Ray3::new(origin, aabb.center() - origin).expect("ray");
    act(&mut h, Action3d::SetRay(Some(ray)));
    click(
        &mut h,
        "Slab test of the ray against the AABB (three slabs)",
    );
    settle(&mut h);
    assert!(three(&h).volumes.slab_test);
    assert!(shows(&h, "max(t_xmin, t_ymin, t_zmin)"));
    for axis in ["x", "y", "z"] {
        assert!(labels(&h).iter().any(|l| l == axis), "a row for {axis}");
    }
    // The ray hits: the answer's stretch is drawn between the last entry and first exit.
    let slab = aabb.slab_test(&ray);
    assert!(slab.t_enter() <= slab.t_exit());
    let drawn = &h.state().ui.view3d.drawn[0];
    assert!(
        drawn
            .overlay
            .iter()
            .any(|s| s.a == ray.at(slab.t_enter()) && s.b == ray.at(slab.t_exit()))
    );
    assert!(
        labels(&h).iter().any(|l| l.contains("z slab")),
        "the legend names the slabs"
    );

    // Parallel to the z slab: z_d = 0, the core and the naive formula agree.
    click(&mut h, "Ray parallel to the z slab (z_d = 0)");
    settle(&mut h);
    let parallel = three(&h).ray.expect("a ray");
    assert_eq!(parallel.dir().z, 0.0);
    assert!(!shows(&h, "NaN compared"));
    // ... and on its plane z = z_min: 0/0 in the naive formula; the core still answers.
    click(&mut h, "…and on its plane z = z_min");
    settle(&mut h);
    let on_plane = three(&h).ray.expect("a ray");
    assert_eq!(on_plane.origin().z, aabb.min.z);
    assert_eq!(on_plane.dir().z, 0.0);
    assert!(shows(&h, "NaN compared"));
    let core_hits = aabb.slab_test(&on_plane).t_enter() <= aabb.slab_test(&on_plane).t_exit();
    let verdict = if core_hits { "hit" } else { "miss" };
    assert!(
        shows(&h, &format!(": {verdict}.")),
        "the core's verdict, {verdict}"
    );
}

#[test]
fn pointing_at_a_row_lights_its_volume_in_the_view() {
    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    let shown = three(&h).volumes;
    act(
        &mut h,
        Action3d::SetVolumes(bvhlab_app::model::volumes3d::Volumes3d {
            toggles: bvhlab_app::model::volumes::VolumeToggles {
                centroid: false,
                ritter: false,
                welzl: false,
                aabb: false,
                obb: false,
                hull: false,
            },
            ..shown
        }),
    );
    settle(&mut h);
    let nothing = h.state().ui.view3d.drawn[0].overlay.len();
    // The table's cell, not the checkbox of the same name.
    let row = h
        .query_all_by_label("AABB")
        .find(|n| n.accesskit_node().role() == egui::accesskit::Role::Label)
        .expect("the AABB's row")
        .rect()
        .center();
    h.hover_at(row);
    settle(&mut h);
    let lit = &h.state().ui.view3d.drawn[0].overlay;
    assert_eq!(
        lit.len(),
        nothing + 12,
        "the AABB's twelve edges, though switched off"
    );
    assert_eq!(
        lit.iter().filter(|s| s.width == 4.0).count(),
        12,
        "drawn thick"
    );
}

#[test]
fn the_volumes_and_the_two_boxes_come_back_from_a_file_and_a_bad_box_is_refused() {
    use bvhlab_app::persist::{open_file, to_file};

    let mut h = lab_3d();
    click(&mut h, "Show the bounding volumes");
    click(&mut h, "the brush (triangles within r of q)");
    click(&mut h, "Separating-axis test of two OBBs (15 axes)");
    settle(&mut h);
    let mut pair = three(&h).obb_pair.expect("on");
    pair.a.degrees = Vec3::new(12.5, -40.0, 7.25);
    pair.step = 9;
    act(&mut h, Action3d::SetObbPair(Some(pair)));
    let collision = bvhlab_app::model::collision3d::Collision3d {
        offset: Vec3::new(0.5, 0.0, 0.25),
        degrees: Vec3::new(0.0, 30.0, 12.5),
        tree: bvhlab_app::model::collision::CollisionTree::Aabb,
        step: Some(3),
    };
    act(&mut h, Action3d::SetCollision(Some(collision)));
    let (volumes, point) = (three(&h).volumes, three(&h).point);
    let file = to_file(h.state().lab());

    let mut fresh = lab_3d();
    act(&mut fresh, open_file(&file).expect("the file opens"));
    for _ in 0..20 {
        fresh.step();
    }
    settle(&mut fresh);
    assert_eq!(three(&fresh).volumes, volumes);
    assert_eq!(three(&fresh).obb_pair, Some(pair));
    assert_eq!(three(&fresh).collision, Some(collision));
    let pairs = |h: &Harness<'_, LabApp>| {
        three(h)
            .collision_run()
            .and_then(|c| c.run.as_ref())
            .map(|r| r.pairs.clone())
    };
    assert_eq!(pairs(&fresh), pairs(&h), "the same answer");
    assert_eq!(three(&fresh).point, point);
    assert!(
        !three(&fresh).display.structure,
        "the trees put away, as when shown"
    );
    let part = |h: &Harness<'_, LabApp>| three(h).part_fits().map(|p| p.triangles.clone());
    assert_eq!(part(&fresh), part(&h), "the same brushed part");

    // A box with a negative half extent or a step past the 15th axis is refused whole.
    let text = String::from_utf8(file).expect("JSON");
    let step = text.replace("\"step\": 9\n", "\"step\": 15\n");
    assert!(step != text, "the file holds the step");
    let refused = open_file(step.as_bytes()).expect_err("refused");
    assert!(refused.contains("0 to 14"), "{refused}");
    let half = text.replacen("\"half\": [", "\"half\": [-", 1);
    let refused = open_file(half.as_bytes()).expect_err("refused");
    assert!(refused.contains("box A"), "{refused}");
}
