//! `rasterlab render`: a mesh, a triangle soup, a line set or a built-in
//! scene drawn to a PNG file, with the time per frame
//! ([`rasterlab::measure::render_request`]).

use super::args::{msaa, Size};
use super::print::progress_bar;
use clap::Args;
use rasterlab::geometry::{ClipPlanes, CullMode, FrontFace, Shading};
use rasterlab::measure::{MeshOverrides, RenderInput, RenderRequest};
use rasterlab::raster::{
    Anisotropic, Blend, BlendMode, DepthState, Derivatives, FillRule, Filter, Interpolation,
    LevelMode, MixSpace, SamplePattern, Wrap, WriteMask,
};
use rasterlab::{Error, Result};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// A mesh (.ply, .ply.gz, .obj), a triangle soup or a line set.
    input: Option<PathBuf>,
    /// Back-end name (see `rasterlab backends`): a triangle back-end
    /// (default scanline), or a line back-end for a line set (default
    /// bresenham).
    #[arg(long)]
    backend: Option<String>,
    /// Target size `WxH` (meshes: 640x480 by default; scenes: their own
    /// size; a 2D file has none, so it is required there).
    #[arg(long)]
    size: Option<Size>,
    /// Fill rule: top-left, bottom-right, top-right, bottom-left,
    /// offscreen-point, inclusive, exclusive.
    #[arg(long, default_value = "top-left")]
    rule: FillRule,
    /// Depth test: never, less, equal, less-equal, greater, not-equal,
    /// greater-equal, always (each with depth writes), or off (no depth
    /// buffer: nothing read or written, the fastest colour-only fill).
    #[arg(long, default_value = "less", value_parser = DepthState::from_name)]
    depth_test: DepthState,
    /// Built-in scene instead of a file: depth-example, split-square,
    /// pinwheel, fan, transparent, cycle (2D), or floor (a checkerboard
    /// receding to the horizon, 320x200, for the texture options).
    #[arg(long, conflicts_with = "input")]
    scene: Option<String>,
    /// Output PNG file.
    #[arg(long)]
    out: PathBuf,
    /// Run even when the estimated work is beyond an hour's worth (the
    /// naive loop on a large mesh).
    #[arg(long)]
    force: bool,
    /// Triangle soups, line sets and scenes: enlarge the picture K times,
    /// each pixel a K x K cell with a grey border (from K = 4), so small
    /// scenes can be seen pixel by pixel.
    #[arg(long, default_value_t = 1)]
    scale: u32,
    /// Render the same view this many times and report the time per frame
    /// (the file is loaded once).
    #[arg(long, default_value_t = 1)]
    frames: u32,
    /// Multisample triangles on the standard pattern of N samples (1, 2,
    /// 4, 8 or 16): depth per sample, shading once per pixel, the samples
    /// averaged into the image.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
    /// How a fragment meets the pixel's colour: replace (default), add,
    /// over (premultiplied fragment), over-straight (straight fragment,
    /// as vertex colours are), multiply.
    #[arg(long, default_value = "replace", value_parser = BlendMode::from_name)]
    blend: BlendMode,
    /// Where colours are mixed (blending, anti-aliased edges, the
    /// multisample resolve): linear (light, the default) or srgb (the
    /// encoded values, as most 2D libraries do).
    #[arg(long, default_value = "linear", value_parser = MixSpace::from_name)]
    mix_in: MixSpace,
    /// The colour channels written, in the order of rgba (say rgb), or none.
    #[arg(long, default_value = "rgba", value_parser = WriteMask::from_name)]
    write_mask: WriteMask,
    /// Triangle soups and scenes: draw the triangles back to front (by
    /// mean depth), as transparent ones need.
    #[arg(long)]
    sort: bool,
    #[command(flatten)]
    mesh: MeshArgs,
}

/// Options for rendering a mesh.
#[derive(Args, Debug)]
pub struct MeshArgs {
    /// Shading: flat, gouraud, diffuse (default), normals, texture.
    #[arg(long)]
    shading: Option<Shading>,
    /// Texture filter for --shading texture: nearest, bilinear (default).
    #[arg(long)]
    filter: Option<Filter>,
    /// An image (PNG) for --shading texture in place of the checkerboard,
    /// on the mesh's uv coordinates (OBJ `vt`).
    #[arg(long, value_name = "FILE.png")]
    texture: Option<PathBuf>,
    /// Mip levels for --shading texture: zero (level 0 only, default),
    /// nearest, linear (trilinear with --filter bilinear).
    #[arg(long)]
    mip: Option<LevelMode>,
    /// Texture wrap mode: repeat (default), clamp, mirror.
    #[arg(long)]
    wrap: Option<Wrap>,
    /// The most anisotropic probes along the footprint, 1 (default) to 16.
    #[arg(long, value_name = "N")]
    anisotropy: Option<u32>,
    /// How anisotropy is filtered: probes (the extension's example,
    /// default) or ewa (Heckbert's elliptical weighted average).
    #[arg(long)]
    anisotropic: Option<Anisotropic>,
    /// Texture coordinate derivatives for --mip and --anisotropy: analytic
    /// (default), quad (2x2 quads, fine), forward (CS184).
    #[arg(long)]
    derivatives: Option<Derivatives>,
    /// Varying interpolation: perspective (correct, the default) or linear
    /// in screen space (the classic mistake; on the bundled meshes it
    /// changes colours by at most 1/255 shaded, 5/255 textured).
    #[arg(long)]
    interpolation: Option<Interpolation>,
    /// Back-face culling: none, back (default), front.
    #[arg(long)]
    cull: Option<CullMode>,
    /// Winding of front faces as seen on screen: ccw (default), cw.
    #[arg(long)]
    front_face: Option<FrontFace>,
    /// Where triangles are clipped at the sides: guard-band (far off
    /// screen, the default) or viewport (the screen's own sides).
    #[arg(long)]
    clip: Option<ClipPlanes>,
    /// Draw the triangle edges over the surface with this line back-end (e.g. bresenham).
    #[arg(long)]
    wireframe: Option<String>,
    /// Camera angle around the vertical axis, degrees (default 0).
    #[arg(long, allow_negative_numbers = true)]
    azimuth: Option<f32>,
    /// Camera angle above the horizon, degrees (default 15).
    #[arg(long, allow_negative_numbers = true)]
    elevation: Option<f32>,
    /// Zoom factor; 1 (the default) frames the whole mesh.
    // Negative numbers are taken as values, so that `--zoom -1` gets the
    // range's message rather than clap's "unexpected argument".
    #[arg(long, allow_negative_numbers = true)]
    zoom: Option<f32>,
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let input = match (&args.scene, &args.input) {
        (Some(name), _) => RenderInput::Scene(name.clone()),
        (None, Some(path)) => RenderInput::File(path.clone()),
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give a mesh, triangle soup or line set file, or --scene NAME".into(),
            ))
        }
    };
    let m = &args.mesh;
    let request = RenderRequest {
        backend: args.backend.clone(),
        size: args.size.map(|s| (s.width, s.height)),
        rule: args.rule,
        depth: args.depth_test,
        blend: Blend {
            mode: args.blend,
            mix_in: args.mix_in,
            write_mask: args.write_mask,
        },
        sort: args.sort,
        mesh: MeshOverrides {
            shading: m.shading,
            filter: m.filter,
            texture: m.texture.clone(),
            mip: m.mip,
            wrap: m.wrap,
            anisotropy: m.anisotropy,
            anisotropic: m.anisotropic,
            derivatives: m.derivatives,
            interpolation: m.interpolation,
            cull: m.cull,
            front_face: m.front_face,
            clip: m.clip,
            wireframe: m.wireframe.clone(),
            azimuth: m.azimuth,
            elevation: m.elevation,
            zoom: m.zoom,
        },
        frames: args.frames,
        scale: args.scale,
        force: args.force,
        msaa: args.msaa,
        ..RenderRequest::new(input, &args.out)
    };
    let bar = progress_bar(u64::from(args.frames), "frames");
    let report = request.run_with_progress(&mut || bar.inc(1));
    bar.finish_and_clear();
    super::print::out(report?)
}
