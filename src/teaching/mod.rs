//! Teaching: what makes each algorithm visible, step by step.
//!
//! * step-by-step traces of every back-end, in the course's terms
//!   (decision variables, edge values, active edges, blocks):
//!   [`trace_triangle`], [`trace_line`], [`trace_depth_buffer`], each a
//!   [`Trace`] (header, columns, rows with their pixels, totals) printed as
//!   text or sent to the lab as JSON;
//! * zoomed pictures of the pixel grid and fill-rule heat maps:
//!   [`GridPicture`];
//! * the one colour-blind safe palette every picture, page and legend
//!   uses, and the legends themselves: [`Role`], [`Legend`];
//! * the side-by-side HTML comparison of every back-end on one input
//!   (images, differences, work and time): [`Report`], and the `compare`
//!   command around it, [`compare()`]; for polygons, filling them directly
//!   counted beside triangulating them: [`ScanOrTriangulate`];
//! * one algorithm traced on a small input, as `explain` prints it:
//!   [`explain()`];
//! * every back-end on the bundled scenes and meshes, its images compared
//!   with the reference's: [`run_demo`];
//! * pixel grids as text, one character a pixel: [`ascii_rows`].
//!
//! ```
//! use rasterlab::raster::{triangle_backend, FillRule};
//! use rasterlab::teaching::trace_triangle;
//!
//! // The bounding-box loop on one triangle: every pixel of its box tested.
//! let bbox = triangle_backend("bbox").unwrap();
//! let trace = trace_triangle(bbox, [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)], FillRule::TopLeft, 6, 4).unwrap();
//! assert!(trace.to_text().ends_with("20 pixels tested, 9 fragments\n"));
//! ```

pub(crate) mod antialias_chart;
pub(crate) mod ascii;
pub(crate) mod compare;
pub(crate) mod demo;
pub(crate) mod explain;
pub(crate) mod grid_picture;
pub(crate) mod level_picture;
pub(crate) mod palette;
pub(crate) mod report;
pub(crate) mod sample_trace;
pub(crate) mod scan_or_triangulate;
pub(crate) mod texture_chart;
pub(crate) mod texture_trace;
pub(crate) mod trace;
pub(crate) mod trace_table;

pub use antialias_chart::{antialias_chart_svg, ChartPoint};
pub use ascii::{ascii_count, ascii_framed, ascii_mark, ascii_rows};
pub use compare::{
    compare, compare_texture_filters, default_compare_size, CompareRequest, CompareSummary,
    TextureSummary,
};
pub use demo::{bundled_assets, run_demo, DemoReport, DemoRow};
pub use explain::{
    explain, Blending, ExplainRequest, Explanation, Texturing, BLEND, BLEND_SCENE, CLIP_TRIANGLE,
    DEFAULT_GRID, DEPTH_BUFFER, TEXTURE,
};
pub use grid_picture::{
    for_people, is_fragment_green, scale_for_people, DepthCells, GridPicture, AS_REFERENCE, GAP,
    INSIDE, MAX_LABELLED_CELLS, MIN_SHORT_SIDE, OVERDRAWN, OVERDRAWN_MORE, TESTED_OUTSIDE,
};
pub use level_picture::LevelPicture;
pub use palette::{
    colour_hex, triangle_colour, triangle_mark, Legend, LegendEntry, Mark, Role, LEVEL_COLOURS,
    MAX_TRIANGLES,
};
pub use report::{
    Antialiasing, BackendRun, CompareInput, Report, RulePicture, ANTIALIAS_PIXELS,
    MAX_REPORT_BYTES, REPORT_BYTES_PER_PIXEL,
};
pub use sample_trace::trace_samples;
pub use scan_or_triangulate::{MethodRow, ScanOrTriangulate};
pub use texture_chart::texture_chart_svg;
pub use texture_trace::trace_texture;
pub use trace::{
    trace_blend, trace_clip, trace_depth_buffer, trace_line, trace_polygon, trace_polygon_rings,
    trace_triangle, trace_triangle_clip, LineEnds, BEHIND_THE_CAMERA,
};
pub use trace_table::{Column, Trace, TraceRow};
