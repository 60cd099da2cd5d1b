//! The built-in meshes: each listed one is made, has triangles, finite vertices, the size
//! its description gives, and is closed and wound outward where it should be (checked by
//! edge pairing and by the signed volume against the shape's known volume); seeds fix the
//! random ones.

use std::collections::HashMap;
use std::f64::consts::PI;

use bvhlab::Mesh;
use bvhlab::glam::{DVec3, Vec3};
use bvhlab_meshio::builtin::{self, LUMPY_SPHERE_SEED, TETRAHEDRA_SEED};

/// Whether every directed edge `a → b` has exactly one partner `b → a`: the surface is closed
/// and consistently wound (an edge-manifold without boundary).
fn closed(mesh: &Mesh) -> bool {
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for &[a, b, c] in mesh.indices() {
        for (from, to) in [(a, b), (b, c), (c, a)] {
            *edges.entry((from, to)).or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

/// The signed volume (divergence theorem: a sum of tetrahedra to the origin), positive for a
/// closed surface wound counter-clockwise seen from outside.
fn volume(mesh: &Mesh) -> f64 {
    mesh.triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = [t.a, t.b, t.c].map(Vec3::as_dvec3);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// `n` with commas between groups of three digits.
fn grouped(n: usize) -> String {
    let digits: Vec<char> = n.to_string().chars().collect();
    let groups: Vec<String> = digits
        .rchunks(3)
        .rev()
        .map(|g| g.iter().collect())
        .collect();
    groups.join(",")
}

#[test]
fn every_listed_mesh_is_made_non_empty_and_finite() {
    let list = builtin::list();
    assert_eq!(list.len(), 7);
    for entry in list {
        let mesh = builtin::make(entry.slug).unwrap_or_else(|| panic!("{} is listed", entry.slug));
        assert!(!mesh.is_empty(), "{}", entry.slug);
        assert!(
            mesh.positions().iter().all(|p| p.is_finite()),
            "{}",
            entry.slug
        );
        assert!(!entry.name.is_empty() && entry.about.ends_with(|c: char| c.is_alphanumeric()));
        // The description gives the mesh's triangle count.
        let count = grouped(mesh.len());
        assert!(
            entry.about.contains(&format!("{count} triangles")),
            "{}: {count}",
            entry.slug
        );
    }
    let mut slugs: Vec<_> = list.iter().map(|b| b.slug).collect();
    slugs.dedup();
    assert_eq!(slugs.len(), list.len());
    assert!(builtin::make("teapot").is_none());
}

#[test]
fn the_cube_is_twelve_axis_aligned_triangles() {
    let cube = builtin::make("cube").expect("built in");
    assert_eq!((cube.len(), cube.positions().len()), (12, 8));
    assert!(closed(&cube));
    assert!((volume(&cube) - 8.0).abs() < 1e-9);
    for t in cube.triangles() {
        let n = (t.b - t.a).cross(t.c - t.a);
        // The normal lies on an axis: two of its components are exactly zero.
        assert_eq!(
            n.to_array().iter().filter(|&&x| x == 0.0).count(),
            2,
            "{t:?}"
        );
    }
}

#[test]
fn closed_shapes_are_closed_and_wound_outward() {
    let sphere = builtin::make("sphere").expect("built in");
    assert_eq!(sphere.len(), 2 * 32 * 15);
    assert!(closed(&sphere));
    // An inscribed polyhedron: a little less than 4π/3.
    let v = volume(&sphere);
    assert!(v < 4.0 * PI / 3.0 && v > 0.97 * 4.0 * PI / 3.0, "{v}");

    let torus = builtin::make("torus").expect("built in");
    assert_eq!(torus.len(), 2 * 48 * 24);
    assert!(closed(&torus));
    // Pappus: 2π R · π r² with R = 1, r = 0.35.
    let exact = 2.0 * PI * PI * 0.35f64.powi(2);
    let v = volume(&torus);
    assert!(v < exact && v > 0.98 * exact, "{v} vs {exact}");

    let bunny = builtin::make("bunny").expect("built in");
    assert_eq!((bunny.len(), bunny.positions().len()), (3674, 1839));
    assert!(closed(&bunny));
    assert!(volume(&bunny) > 0.0);
}

#[test]
fn each_tetrahedron_is_closed_and_wound_outward() {
    let cloud = builtin::make("tetrahedra").expect("built in");
    assert_eq!(cloud.len(), 2000);
    assert!(closed(&cloud));
    for (k, four) in cloud.triangles().chunks(4).enumerate() {
        let v: f64 = four
            .iter()
            .map(|t| {
                let [a, b, c] = [t.a, t.b, t.c].map(Vec3::as_dvec3);
                a.dot(b.cross(c)) / 6.0
            })
            .sum();
        // Regular, circumradius s: edge s·√(8/3), volume edge³ / (6√2).
        let corner = four[0].a.as_dvec3();
        let centre: DVec3 = four.iter().map(|t| t.a.as_dvec3()).sum::<DVec3>() / 4.0;
        let s = (corner - centre).length();
        let edge = s * (8.0f64 / 3.0).sqrt();
        let exact = edge.powi(3) / (6.0 * 2f64.sqrt());
        assert!(
            (v - exact).abs() < 1e-3 * exact,
            "tetrahedron {k}: {v} vs {exact}"
        );
        assert!(
            (0.03 - 1e-6..0.12 + 1e-6).contains(&s),
            "tetrahedron {k}: size {s}"
        );
    }
}

#[test]
fn the_large_mesh_has_a_million_triangles_and_is_closed() {
    let lumpy = builtin::make("lumpy-sphere").expect("built in");
    assert!(lumpy.len() >= 1_000_000, "{}", lumpy.len());
    assert!(closed(&lumpy));
    let radii = lumpy.positions().iter().map(|p| p.length());
    let (lo, hi) = radii.fold((f32::INFINITY, 0.0f32), |(lo, hi), r| {
        (lo.min(r), hi.max(r))
    });
    assert!(
        lo > 0.6 && hi < 1.4 && hi - lo > 0.1,
        "radius from {lo} to {hi}"
    );
    assert!(volume(&lumpy) > 0.0);
}

#[test]
fn seeds_fix_the_random_meshes() {
    assert_eq!(builtin::tetrahedra(50, 7), builtin::tetrahedra(50, 7));
    assert_ne!(builtin::tetrahedra(50, 7), builtin::tetrahedra(50, 8));
    assert_eq!(
        builtin::make("tetrahedra"),
        Some(builtin::tetrahedra(500, TETRAHEDRA_SEED))
    );
    assert_eq!(
        builtin::lumpy_sphere(40, 21, 3),
        builtin::lumpy_sphere(40, 21, 3)
    );
    assert_ne!(
        builtin::lumpy_sphere(40, 21, 3),
        builtin::lumpy_sphere(40, 21, 4)
    );
    let small = builtin::lumpy_sphere(40, 21, LUMPY_SPHERE_SEED);
    assert_eq!(small.len(), 2 * 40 * 20);
    assert!(closed(&small));
}

#[test]
fn generators_clamp_degenerate_sizes() {
    assert_eq!(builtin::uv_sphere(0, 0).len(), 2 * 3);
    assert!(closed(&builtin::uv_sphere(1, 1)));
    assert_eq!(builtin::torus(1, 2, 0.2).len(), 2 * 3 * 3);
    assert!(builtin::tetrahedra(0, 1).is_empty());
}

#[test]
fn the_twisting_torus_is_a_closed_function_of_time_with_fixed_indices() {
    let slug = builtin::TWISTING_TORUS;
    assert!(builtin::deforms(slug) && !builtin::deforms("torus"));
    assert!(builtin::make_at("torus", 1.0).is_none());
    assert_eq!(builtin::make(slug), builtin::make_at(slug, 0.0));
    let start = builtin::make_at(slug, 0.0).expect("it moves");
    assert_eq!((start.len(), start.positions().len()), (4_096, 2_048));
    for seconds in [0.0, 0.25, 1.7, 12.5, 3_600.0] {
        let mesh = builtin::make_at(slug, seconds).expect("it moves");
        assert_eq!(
            mesh,
            builtin::make_at(slug, seconds).expect("again"),
            "{seconds} s"
        );
        assert_eq!(mesh.indices(), start.indices(), "only the vertices move");
        assert!(mesh.positions().iter().all(|p| p.is_finite()));
        assert!(closed(&mesh), "{seconds} s");
        assert!(volume(&mesh) > 0.0, "wound outward at {seconds} s");
        assert_eq!(mesh.summary().degenerate_triangles, 0, "{seconds} s");
        // The ring stays around the axis: no vertex crosses it.
        assert!(
            mesh.positions()
                .iter()
                .all(|p| (p.x * p.x + p.z * p.z).sqrt() > 0.4),
            "{seconds} s"
        );
    }
    let later = builtin::make_at(slug, 0.5).expect("it moves");
    let moved = start
        .positions()
        .iter()
        .zip(later.positions())
        .filter(|(a, b)| a.distance(**b) > 1e-3)
        .count();
    assert!(
        moved > 2_000 / 2,
        "half a second moves most vertices: {moved}"
    );
}
