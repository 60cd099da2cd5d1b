//! What a newcomer ran into in issue 33: two `AabbTree` names, `structure::bvh::AabbTree<P>`
//! and `AabbTree3`, that looked unrelated. Now the generic `AabbTree<P>` (and `SphereTree<P>`,
//! `ObbTree<P>`) is in the prelude and at the crate root, and the 2D/3D names are its forms
//! over segments and triangles: one type each, as these assignments show (they would not
//! compile if the names were different types).

use bvhlab::glam::{Vec2, Vec3};
use bvhlab::prelude::*;
// The name the newcomer found first, in the module that defines it.
use bvhlab::structure::bvh::AabbTree as ModuleAabbTree;

#[test]
fn the_dimension_names_are_the_generic_trees_over_triangles_and_segments() {
    let tris = [Triangle3::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
    let generic: AabbTree<Triangle3> = AabbTree3::build(&tris);
    let named: AabbTree3 = generic.clone();
    assert_eq!(named, ModuleAabbTree::<Triangle3>::build(&tris));
    let spheres: SphereTree<Triangle3> = SphereTree3::build(&tris);
    let obbs: ObbTree<Triangle3> = ObbTree3::build(&tris);
    assert_eq!(spheres.primitives().len() + obbs.primitives().len(), 2);

    let segments = [Segment2::new(Vec2::ZERO, Vec2::X)];
    let flat: AabbTree<Segment2> = AabbTree2::build(&segments);
    let _: SphereTree<Segment2> = SphereTree2::build(&segments);
    let _: ObbTree<Segment2> = ObbTree2::build(&segments);
    assert_eq!(flat.primitives(), &segments);

    // Over any other primitive, the same generic name: points, here.
    let points = [Vec3::ZERO, Vec3::ONE];
    let cloud = AabbTree::<Vec3>::build(&points);
    assert_eq!(
        cloud.closest_point(Vec3::splat(0.9)).map(|n| n.prim),
        Some(1)
    );
}
