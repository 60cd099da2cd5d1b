//! Every structure against brute force on the real meshes in `../shared/data/meshes`
//! (skipped, with a message, when that folder is absent).

use bvhlab::mesh::Mesh;
use bvhlab::prelude::*;
use bvhlab::structure::BruteForce;
use bvhlab::{Aabb3, SpatialIndex, Triangle3};
use bvhlab_tests::conformance::{Budget, check_against_brute_force};
use bvhlab_tests::scenes::Scene;
use bvhlab_tests::{mesh_dir, rng};

/// The meshes and how many queries each gets (brute force is the slow side).
const MESHES: [(&str, usize, usize); 7] = [
    ("suzanne.obj", 150, 40),
    ("spot.obj", 100, 25),
    ("fandisk.obj", 100, 25),
    ("teapot.obj", 100, 25),
    ("stanford-bunny.obj", 25, 8),
    ("dragon.obj", 10, 3),
    ("ogre.obj", 10, 3),
];

fn load(name: &str) -> Option<Scene<Triangle3>> {
    let Some(dir) = mesh_dir() else {
        eprintln!("skipping {name}: ../shared/data/meshes is not beside the repository");
        return None;
    };
    let bytes = std::fs::read(dir.join(name)).expect("the shared meshes are readable");
    let mesh = Mesh::from_obj(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
    Some(Scene {
        name: name.into(),
        prims: mesh.triangles().to_vec(),
    })
}

/// 50 of the mesh's own triangles, shifted by 1% of its size: a collider that really
/// intersects it, small enough for brute force to check every pair.
fn collider_for(scene: &Scene<Triangle3>) -> Scene<Triangle3> {
    let bounds = scene
        .prims
        .iter()
        .fold(Aabb3::EMPTY, |b, t| b.merge(&t.bounds()));
    let shift = bounds.size() * 0.01;
    let step = (scene.prims.len() / 50).max(1);
    let prims = scene
        .prims
        .iter()
        .step_by(step)
        .map(|t| Triangle3::new(t.a + shift, t.b + shift, t.c + shift))
        .collect();
    Scene {
        name: format!("{} shifted", scene.name),
        prims,
    }
}

fn run<S: SpatialIndex<Prim = Triangle3>>(seed: u64) {
    let mut rng = rng(seed);
    for (name, rays, points) in MESHES {
        let Some(scene) = load(name) else { return };
        check_against_brute_force::<S>(
            &mut rng,
            &scene,
            &collider_for(&scene),
            &Budget { rays, points },
        );
    }
}

macro_rules! on_meshes {
    ($($test:ident: $structure:ty),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                run::<$structure>(7);
            }
        )*
    };
}

on_meshes! {
    brute_force: BruteForce<Triangle3>,
    aabb_tree: AabbTree3,
    sphere_tree: SphereTree3,
    obb_tree: ObbTree3,
    kd_tree: KdTree3,
    bsp_tree: Bsp3,
    grid: Grid3,
    octree: Octree3,
}
