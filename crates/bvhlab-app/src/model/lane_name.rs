//! What a lane is called on the canvas and in the step-through panel. Two lanes of the same
//! structure (the lecture's construction question: median against SAH) would both read
//! "AABB tree"; beside each other they are named by the build options that differ.

use bvhlab::structure::bvh::{SphereFit, SplitMethod};

use super::structures::{BuildSettings, KdSplit, StructureKind};

/// `settings`' structure in `dim` dimensions, followed, when `other` is the same structure,
/// by each build option of `settings` that differs from `other`'s ("AABB tree, SAH split"
/// beside "AABB tree, object-median split").
pub fn lane_name(settings: &BuildSettings, other: Option<&BuildSettings>, dim: usize) -> String {
    let mut name = settings.kind.label_in(dim).to_owned();
    let Some(other) = other.filter(|o| o.kind == settings.kind) else {
        return name;
    };
    let kind = settings.kind;
    let mut differs = Vec::new();
    if kind.is_bvh() && settings.bvh_split != other.bvh_split {
        differs.push(bvh_split_words(settings.bvh_split).to_owned());
    }
    if kind == StructureKind::SphereTree && settings.sphere_fit != other.sphere_fit {
        differs.push(match settings.sphere_fit {
            SphereFit::Ritter => "Ritter spheres".to_owned(),
            SphereFit::Welzl => "Welzl spheres".to_owned(),
        });
    }
    if kind == StructureKind::KdTree && settings.kd_split != other.kd_split {
        differs.push(
            match settings.kd_split {
                KdSplit::MedianRoundRobin => "median planes, axes in turn",
                KdSplit::MedianLongest => "median planes, longest axis",
                KdSplit::Sah => "SAH planes",
            }
            .to_owned(),
        );
    }
    if kind == StructureKind::Grid && settings.grid_cells != other.grid_cells {
        differs.push(match settings.grid_cells {
            0 => "cells chosen automatically".to_owned(),
            n => format!("{n} cells per axis"),
        });
    }
    if kind == StructureKind::Quadtree && settings.quadtree_depth != other.quadtree_depth {
        differs.push(format!("depth at most {}", settings.quadtree_depth));
    }
    if kind != StructureKind::Grid && settings.leaf_size != other.leaf_size {
        differs.push(format!("leaf size {}", settings.leaf_size));
    }
    for part in differs {
        name.push_str(", ");
        name.push_str(&part);
    }
    name
}

/// The BVH split method in the lecture's words.
fn bvh_split_words(split: SplitMethod) -> &'static str {
    match split {
        SplitMethod::SpatialMedian => "split at the middle of the longest axis",
        SplitMethod::ObjectMedian => "object-median split",
        SplitMethod::BinnedSah => "SAH split",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_lanes_of_one_structure_are_named_by_the_options_that_differ() {
        let sah = BuildSettings {
            kind: StructureKind::AabbTree,
            bvh_split: SplitMethod::BinnedSah,
            ..BuildSettings::default()
        };
        let median = BuildSettings {
            bvh_split: SplitMethod::ObjectMedian,
            leaf_size: sah.leaf_size + 2,
            ..sah
        };
        assert_eq!(lane_name(&sah, None, 2), "AABB tree");
        assert_eq!(
            lane_name(&sah, Some(&median), 2),
            format!("AABB tree, SAH split, leaf size {}", sah.leaf_size)
        );
        assert_eq!(
            lane_name(&median, Some(&sah), 2),
            format!(
                "AABB tree, object-median split, leaf size {}",
                median.leaf_size
            )
        );
        let kd = BuildSettings {
            kind: StructureKind::KdTree,
            ..sah
        };
        assert_eq!(
            lane_name(&kd, Some(&sah), 3),
            "k-d tree",
            "different structures: their names"
        );
        let octree = BuildSettings {
            kind: StructureKind::Quadtree,
            quadtree_depth: 5,
            ..sah
        };
        let deeper = BuildSettings {
            quadtree_depth: 9,
            ..octree
        };
        assert_eq!(
            lane_name(&octree, Some(&deeper), 3),
            "octree, depth at most 5"
        );
    }
}
