//! Measurement: the workloads every back-end is timed on, the benchmark
//! that times them, and what makes a figure trustworthy.
//!
//! * [`workload`]: named, repeatable inputs (large fills, many small
//!   triangles, meshes, line sets) prepared once and drawn many times;
//! * [`render_request`]: one `rasterlab render` as a value (input,
//!   choices, output file), run on the fast path frame after frame into
//!   a report with the time per frame;
//! * [`benchmark`]: the table, JSON and chart of `rasterlab bench`;
//! * [`Timing`] and [`time_runs`]: a warm-up, timed runs, their minimum, median and maximum;
//! * [`rounds`]: rasterlab and its peers timed in interleaved rounds, and
//!   the ratio table of `cargo bench --bench side_by_side`;
//! * [`CpuUse`]: the CPU time each thread got, and the time it waited for a
//!   core, beside the wall time;
//! * [`context`]: the commit, machine and load a run was measured on;
//! * [`data`]: where the Stanford models that are not bundled are found,
//!   and the skipped row when they are not;
//! * [`Table`]: plain-text tables with aligned columns.

pub mod benchmark;
pub mod context;
mod cpu;
pub mod data;
pub mod render_request;
pub mod rounds;
mod table;
mod timing;
pub mod workload;

pub use cpu::{CpuUse, ThreadTimes};
pub use table::{significant, Table};
pub use timing::{time_runs, Spread, Timing};
