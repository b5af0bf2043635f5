//! Clusters: graphs used as nodes.
//!
//! A graph declares its interface with `graph.input` and `graph.output` nodes ([`interface`]). A
//! `cluster` node references such a graph file or embeds the subgraph inline; its ports are the
//! subgraph's inputs and outputs. Each cluster instance keeps its own copy of the subgraph and its own
//! [`Evaluator`](crate::Evaluator), so evaluation inside is incremental (only what depends on a
//! changed input re-runs, with the same early cutoff) and two instances cache separately.
//! [`edit`] turns a selection into a cluster and explodes a cluster back into its nodes.

pub mod edit;
pub mod instance;
pub mod interface;

pub use edit::{explode, make_cluster};
pub use instance::{CLUSTER_TYPE, Cluster, ClusterSource, cluster_type_description};
pub use interface::{INPUT_TYPE, Interface, InterfacePort, OUTPUT_TYPE, nodes, parse_port_type};
