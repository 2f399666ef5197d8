//! The picture every course shows of mipmapping: the receding floor
//! coloured by the mip level each pixel reads (Williams 1983), the level
//! nearest its `lambda` (OpenGL 3.3, section 3.8.11), so the bands where
//! the level changes can be seen running to the horizon; with
//! anisotropic probes, the level of the probes.
//!
//! ```
//! use rasterlab::geometry::Floor;
//! use rasterlab::raster::{Derivatives, Sampler};
//! use rasterlab::teaching::LevelPicture;
//!
//! let floor = Floor::new(64, 40).unwrap();
//! let picture = LevelPicture::new(&floor, Sampler::default(), Derivatives::Quad, None);
//! assert!(picture.levels.iter().flatten().any(|&l| l > 0));
//! assert!(picture.to_svg().contains("class=\"legend\""));
//! ```

use crate::error::{Error, Result};
use crate::geometry::Floor;
use crate::markup::Markup;
use crate::raster::derivatives::Derivatives;
use crate::raster::texture::{Footprint, LevelMode, Sampler};
use crate::teaching::palette::{colour_hex, Legend, LegendEntry, Mark, Role, LEVEL_COLOURS};

/// Each pixel drawn as a square this many picture units wide.
const ZOOM: u32 = 2;

/// The floor's pixels by the mip level they read.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelPicture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row by row, each pixel's level, `None` off the floor.
    pub levels: Vec<Option<usize>>,
    /// A pixel marked (the traced one), if any.
    pub mark: Option<(u32, u32)>,
    /// The texture's levels.
    pub count: usize,
}

impl LevelPicture {
    /// The levels of `floor` under `sampler`'s anisotropy, derivatives by
    /// `method`; `mark` framed.
    pub fn new(
        floor: &Floor,
        sampler: Sampler,
        method: Derivatives,
        mark: Option<(u32, u32)>,
    ) -> LevelPicture {
        let texture = floor.texture();
        let count = texture.levels().len();
        let (w, h) = (texture.width(), texture.height());
        let mut levels = Vec::with_capacity(floor.width() as usize * floor.height() as usize);
        for y in 0..floor.height() {
            for x in 0..floor.width() {
                levels.push(floor.planes_at(x, y).map(|planes| {
                    let g = planes.derivatives(method, i64::from(x), i64::from(y));
                    let probes = Footprint::new(g.dx, g.dy, w, h).probes(sampler.anisotropy);
                    LevelMode::Nearest.choose(probes.lambda, count).fine
                }));
            }
        }
        LevelPicture {
            width: floor.width(),
            height: floor.height(),
            levels,
            mark,
            count,
        }
    }

    /// Level `level`'s colour: coarser levels than the palette has share
    /// its last.
    fn colour(level: usize) -> [u8; 3] {
        LEVEL_COLOURS[level.min(LEVEL_COLOURS.len() - 1)]
    }

    /// The legend: a swatch per level shown, the sky, the marked pixel.
    fn legend(&self) -> Legend {
        let last = LEVEL_COLOURS.len() - 1;
        let mut legend = Legend::default();
        let shown = |l: usize| self.levels.iter().flatten().any(|&v| v.min(last) == l);
        for l in (0..self.count.min(LEVEL_COLOURS.len())).filter(|&l| shown(l)) {
            let label = if l == last && self.count > LEVEL_COLOURS.len() {
                format!("level {l} and coarser")
            } else {
                format!("level {l}")
            };
            legend.entries.push(LegendEntry {
                key: format!("level-{l}"),
                rgb: LevelPicture::colour(l),
                mark: Mark::Fill,
                label,
            });
        }
        legend.entries.push(LegendEntry {
            key: "sky".into(),
            rgb: [255, 255, 255],
            mark: Mark::Fill,
            label: "no floor (sky)".into(),
        });
        if self.mark.is_some() {
            legend = legend.with_mark(Role::Geometry, Mark::Frame, "the pixel traced");
        }
        legend
    }

    /// The picture as SVG: the pixels as runs of one level, the legend
    /// under them.
    pub fn to_svg(&self) -> String {
        let (pw, ph) = (f64::from(self.width * ZOOM), f64::from(self.height * ZOOM));
        let margin = 10.0;
        let width = (pw + 2.0 * margin).max(420.0);
        let (legend_svg, legend_h) = self
            .legend()
            .to_svg(margin, ph + 40.0, width - 2.0 * margin);
        let height = ph + 44.0 + legend_h;
        let z = f64::from(ZOOM);
        let mut m = Markup::new();
        m.open_svg(width, height, Some(12)).newline();
        m.empty(
            "rect",
            &[("width", &"100%"), ("height", &"100%"), ("fill", &"white")],
        );
        m.element(
            "text",
            &[
                ("x", &margin),
                ("y", &20),
                ("font-size", &14),
                ("font-weight", &"bold"),
            ],
            &format!(
                "The mip level each pixel of the floor reads ({} x {}, {} levels)",
                self.width, self.height, self.count
            ),
        )
        .newline();
        let top = 30.0;
        for y in 0..self.height {
            let row = &self.levels[(y * self.width) as usize..((y + 1) * self.width) as usize];
            let mut x = 0;
            while x < row.len() {
                let run = row[x..].iter().take_while(|&&l| l == row[x]).count();
                if let Some(level) = row[x] {
                    m.empty(
                        "rect",
                        &[
                            ("x", &(margin + x as f64 * z)),
                            ("y", &(top + f64::from(y) * z)),
                            ("width", &(run as f64 * z)),
                            ("height", &z),
                            ("fill", &colour_hex(LevelPicture::colour(level))),
                        ],
                    );
                }
                x += run;
            }
        }
        m.empty(
            "rect",
            &[
                ("x", &margin),
                ("y", &top),
                ("width", &pw),
                ("height", &ph),
                ("fill", &"none"),
                ("stroke", &"#999"),
            ],
        );
        if let Some((x, y)) = self.mark {
            m.empty(
                "rect",
                &[
                    ("x", &(margin + f64::from(x) * z - 2.0)),
                    ("y", &(top + f64::from(y) * z - 2.0)),
                    ("width", &(z + 4.0)),
                    ("height", &(z + 4.0)),
                    ("fill", &"none"),
                    ("stroke", &colour_hex(Role::Geometry.rgb())),
                    ("stroke-width", &2),
                ],
            );
        }
        m.raw(&legend_svg);
        m.close("svg");
        m.finish()
    }

    /// Writes the picture as SVG, or as PNG (with the `png-text` feature,
    /// on by default), by the path's extension.
    pub fn save(&self, path: &std::path::Path) -> Result<()> {
        crate::output::check_file(path, &["svg", "png"])?;
        let svg = self.to_svg();
        if crate::output::extension(path).as_deref() == Some("svg") {
            return crate::output::write_file(path, svg.as_bytes());
        }
        #[cfg(feature = "png-text")]
        if let Some(png) = crate::output::svg_to_png(&svg) {
            return crate::output::write_png(path, &png);
        }
        Err(Error::InvalidArgument(format!(
            "{}: this build writes the level picture as .svg only",
            path.display()
        )))
    }
}
