//! The core's integration tests in one test binary: each file beside this one is a module
//! (linking one binary instead of one per file is most of what `cargo test` spent; issue 28).
//! One file's tests: `cargo test -p bvhlab --features serde,parallel --test all saved_trees::`.
//! The tests of the `serde` and `parallel` features compile only with those features on.

mod bvh_common;
mod grid_support;
mod kdtree_bsp_common;
mod obb_common;
mod overlap_common;

mod batch_queries;
mod bsp;
mod bvh4_blocks;
mod bvh4_queries;
mod bvh4_range_whole_nodes;
mod bvh4_updates;
mod bvh_build;
mod bvh_build_job;
mod bvh_degenerate;
mod bvh_events;
mod bvh_fast;
mod bvh_fast_build;
mod bvh_meshes;
mod bvh_parallel_build;
mod bvh_proptest;
mod bvh_queries;
mod bvh_refit;
mod bvh_updates;
mod bvh_wide_closest;
mod example_save_load;
mod grid;
mod grid_props;
mod grid_updates;
mod hull;
mod kdtree;
mod kdtree_point_cloud;
mod lecture;
mod mesh;
mod mesh_fuzz;
mod mesh_indexed;
mod newcomer;
mod newcomer_bounds;
mod newcomer_names;
mod newcomer_spatial_query;
mod newcomer_validate;
mod obb;
mod obb_queries;
mod obb_sat;
mod octree;
mod overlap_box;
mod overlap_pair;
mod query_traits;
mod saved_trees;
mod triangle_ray_exact;
