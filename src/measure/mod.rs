//! Measurement: the workloads every back-end is timed on, the benchmark
//! that times them, and what makes a figure trustworthy.
//!
//! * named, repeatable inputs (large fills, many small triangles, meshes,
//!   line sets) prepared once and drawn many times: [`TriangleWorkload`]
//!   ([`fill`], [`sized`], [`slivers`]) and [`LineWorkload`];
//! * one `rasterlab render` as a value ([`RenderRequest`]: input, choices,
//!   output file), run on the fast path frame after frame into a
//!   [`RenderReport`] with the time per frame;
//! * the timings of `rasterlab bench`: [`run`] with [`BenchOptions`] into
//!   a [`BenchReport`], which the program writes out as a table, JSON and
//!   a chart;
//! * a warm-up, timed runs, their minimum, median and maximum: [`Timing`]
//!   and [`time_runs`];
//! * rasterlab and its peers timed in interleaved rounds, and the ratio
//!   table of `cargo bench --bench side_by_side`: [`Contender`],
//!   [`Workload`], [`Ratio`];
//! * the CPU time each thread got, and the time it waited for a core,
//!   beside the wall time: [`CpuUse`];
//! * the commit, machine and load a run was measured on: [`Context`];
//! * where the Stanford models that are not bundled are found, and the
//!   skipped row when they are not: [`find`], [`Skipped`];
//! * plain-text tables with aligned columns: [`Table`];
//! * anti-aliasing compared: each sampling method's coverage against the
//!   exact area ([`compare_antialiasing`], [`Method`]);
//! * texture filtering compared: each filter, level mode, derivative
//!   method and anisotropy on the receding floor against the texture over
//!   each pixel, and its cost ([`compare_textures`]).
//!
//! ```
//! use rasterlab::measure::{sized, time_runs};
//! use rasterlab::raster::{triangle_backend, RenderTarget};
//!
//! // Many small triangles on a 64 x 64 target, drawn by the scanline
//! // back-end: one warm-up, then five timed runs.
//! let workload = sized(64, 64, 4.0);
//! let scanline = triangle_backend("scanline").unwrap();
//! let mut target = RenderTarget::new(64, 64).unwrap();
//! let (timing, samples) = time_runs(5, || workload.run(scanline, &mut target));
//! assert!(samples > 0);
//! let t = timing.spread;
//! assert!(t.min_ms <= t.median_ms && t.median_ms <= t.max_ms);
//! ```

pub(crate) mod antialias;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) mod benchmark;
pub(crate) mod context;
mod cpu;
pub(crate) mod data;
mod fast_lines;
mod render_floor;
pub(crate) mod render_request;
pub(crate) mod rounds;
mod table;
pub(crate) mod texture_compare;
mod timing;
pub(crate) mod workload;

pub use antialias::{
    compare_antialiasing, coverage_error, coverage_of, AntialiasRow, Coverage, ErrorSummary,
    Method, METHODS,
};
pub use benchmark::{run, BenchOptions, BenchReport, Measurement, Progress, WorkloadSet, BASELINE};
pub use context::{Context, Machine, COMMIT};
pub use cpu::CpuUse;
pub use data::{data_dir, find, find_in, Skipped, DRAGON_RES2, FULL_DRAGON};
pub use render_request::{
    DrawingReport, MeshOverrides, MeshReport, RenderInput, RenderReport, RenderRequest, MAX_SCALE,
    RENDER_CULL,
};
pub use rounds::{
    ratio_header, Contender, Figure, Ratio, Side, WarmRatio, Workload, WorkloadResult,
};
pub use table::{significant, Table};
pub use texture_compare::{compare_textures, TextureComparison, TextureMethod, TextureRow};
pub use timing::{time_runs, Spread, Timing};
pub use workload::{fill, long_lines, short_lines, sized, slivers, LineWorkload, TriangleWorkload};
// What only the `rasterlab` program uses; absent without the `cli` feature.
#[cfg(feature = "cli")]
pub use self::benchmark::{to_json, write_outputs};
