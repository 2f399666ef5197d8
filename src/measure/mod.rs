//! Measurement: the workloads every back-end is timed on, and the
//! benchmark that times them.
//!
//! * [`workload`]: named, repeatable inputs (large fills, many small
//!   triangles, meshes, line sets) prepared once and drawn many times;
//! * [`benchmark`]: medians over runs, the table, JSON and chart of
//!   `rasterlab bench`.

pub mod benchmark;
pub mod workload;
