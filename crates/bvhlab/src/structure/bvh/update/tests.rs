//! Unit tests that need the search's internals: how many nodes it looks at.

use glam::Vec3;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::search::{Item, Limits};
use crate::structure::bvh::{AabbTree, NodeVolume};
use crate::{Primitive, Triangle3};

fn triangles(rng: &mut ChaCha8Rng, n: usize) -> Vec<Triangle3> {
    let mut v = |scale: f32| {
        Vec3::new(
            rng.random_range(-scale..scale),
            rng.random_range(-scale..scale),
            rng.random_range(-scale..scale),
        )
    };
    (0..n)
        .map(|_| {
            let a = v(10.0);
            Triangle3::new(a, a + v(0.2), a + v(0.2))
        })
        .collect()
}

/// The branch and bound prunes: placing a small triangle in a tree of 20 000 looks at a
/// few dozen nodes on average, not the thousands there are (a search that pruned nothing
/// would look at all of them).
#[test]
fn the_search_looks_at_few_nodes() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let tree = AabbTree::<Triangle3>::build(&triangles(&mut rng, 20_000));
    let limits = Limits {
        depth: 64,
        heights: None,
        leaf_size: 4,
        full_leaves: false,
    };
    let probes = triangles(&mut rng, 500);
    let visited: usize = probes
        .iter()
        .map(|t| {
            let item = Item {
                volume: NodeVolume::fit(&t.bounds(), &[], tree.options()),
                prims: Some(1),
                height: 0,
            };
            tree.cheapest_place(&item, &limits)
                .expect("a place")
                .visited
        })
        .sum();
    let mean = visited as f64 / probes.len() as f64;
    let nodes = tree.nodes().len();
    assert!(
        mean < 100.0,
        "the search looks at {mean} nodes of {nodes} on average"
    );
}
