//! Teaching: what makes each algorithm visible, step by step.
//!
//! * [`trace`]: step-by-step traces of every back-end, in the course's
//!   terms (decision variables, edge values, active edges, blocks);
//! * [`trace_table`]: a trace as data (header, columns, rows with their
//!   pixels, totals), printed as text or sent to the lab as JSON;
//! * [`grid_picture`]: zoomed pictures of the pixel grid and fill-rule
//!   heat maps;
//! * [`palette`]: the one colour-blind safe palette every picture, page
//!   and legend uses, and the legends themselves;
//! * [`report`]: the side-by-side HTML comparison of every back-end on
//!   one input (images, differences, work and time);
//! * [`ascii`]: pixel grids as text, one character a pixel;
//! * [`compare`]: the `compare` command: an input file, every back-end, the report;
//! * [`explain`]: one algorithm traced on a small input, as `explain` prints it;
//! * [`demo`]: every back-end on the bundled scenes and meshes, its
//!   images compared with the reference's.

pub mod ascii;
pub mod compare;
pub mod demo;
pub mod explain;
pub mod grid_picture;
pub mod palette;
pub mod report;
pub mod trace;
pub mod trace_table;
