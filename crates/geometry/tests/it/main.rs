//! The geometry crate's integration tests, one test binary: each module is what was a
//! `tests/<name>.rs` binary. Run one module's tests with
//! `cargo test -p <this crate> --test it <module>::`.

#[path = "../common/mod.rs"]
mod common;
mod cone_check;
mod configurations;
mod conical_support;
mod coplanar_columns;
mod correction;
mod correction_blend;
mod cut_by_plane;
mod encode_roundtrip;
mod end_planes;
#[path = "../fab_common/mod.rs"]
mod fab_common;
mod fabrication_proptest;
mod hand_checked;
mod hostile;
mod inputs_broadcast;
mod mirror_join;
mod monge_equivalence;
mod parallel_support;
mod parallel_transform;
mod planarity;
mod refinement;
mod strips;
mod subdivide_rows;
mod support_strips;
mod thread_count;
mod toolbox_props;
mod translational;
mod unroll;
mod unroll_cut_mesh;
mod unroll_folds;
mod unroll_marks;
mod unroll_split;
mod vertex_on_directrix;
mod wide_vectors;
