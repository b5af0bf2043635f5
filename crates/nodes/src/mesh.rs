//! Mesh operations: conversion to polygons, cutting by a plane, mirroring, joining.

use cnets_engine::NodeDef;

/// Every node of this module.
pub fn nodes() -> Vec<NodeDef> {
    vec![]
}
