//! The nodes crate's integration tests, one test binary: each module is what was a
//! `tests/<name>.rs` binary. Run one module's tests with
//! `cargo test -p <this crate> --test it <module>::`.
//! Kept as binaries of their own (process-wide state: an allocator, a budget): `budget_props.rs`, `reader_limits.rs`.

mod construction_nodes;
mod export_dxf_ezdxf;
mod export_errors;
mod export_gltf_validator;
mod export_json_csv;
mod export_obj_tobj;
mod export_svg_xml;
#[path = "../fab_support/mod.rs"]
mod fab_support;
mod fabrication_demo_graph;
mod fabrication_nodes;
mod file_reads_tracked;
mod hostile_inputs;
mod imported_profile_graph;
mod inputs_demo_graph;
mod lazy_construction;
mod mapper_in_graph_files;
mod mesh_nodes;
mod node_contracts;
mod panel_schedule;
mod port_hints;
mod ratio_tables;
mod read_mesh_files;
mod read_polylines_dxf;
mod read_polylines_files;
mod surface_distance;
mod toolbox_contracts;
mod unroll_workshop;
