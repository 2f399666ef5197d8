//! Measurement: the workloads every back-end is timed on, the benchmark
//! that times them, and what makes a figure trustworthy.
//!
//! * [`workload`]: named, repeatable inputs (large fills, many small
//!   triangles, meshes, line sets) prepared once and drawn many times;
//! * [`benchmark`]: the table, JSON and chart of `rasterlab bench`;
//! * [`timing`]: a warm-up, timed runs, their minimum, median and maximum;
//! * [`cpu`]: the CPU time each thread got, and the time it waited for a
//!   core, beside the wall time;
//! * [`context`]: the commit, machine and load a run was measured on;
//! * [`table`]: plain-text tables with aligned columns.

pub mod benchmark;
pub mod context;
pub mod cpu;
pub mod table;
pub mod timing;
pub mod workload;
