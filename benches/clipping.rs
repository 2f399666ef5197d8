//! What clipping at the viewport's own planes costs beside the guard
//! band (`render --clip viewport|guard-band`), in interleaved rounds
//! (`rasterlab::measure::rounds`), one thread.
//!
//! Views, at 1920x1080, back faces culled, Gouraud shading, azimuth 30:
//!
//! * `zoom2.5`: the camera of `render --zoom 2.5`, the dragon crossing
//!   every side of the screen;
//! * `inside`: `--zoom 12`, the camera among the dragon's coils, so that
//!   triangles cross the near plane too.
//!
//! Each view of the bundled dragon (`dragon_res4`, 11,102 triangles) and,
//! when the data folder holds it, of the full one (`dragon`, 871,414),
//! is timed two ways under each clip mode: the geometry alone (vertex
//! shader, clipping, set-up: `MeshRenderer::geometry`) and the whole
//! frame with `scanline`. Before the rounds, each mode's pipeline counts
//! are printed (rejected, clipped, culled, no pixel centre, rasterized)
//! with the fragments drawn.
//!
//! ```text
//! cargo bench --bench clipping                       # everything, 10 rounds
//! cargo bench --bench clipping -- --rounds 5 inside  # views named *inside*
//! ```

use rasterlab::geometry::{ClipPlanes, CullMode, Mesh, MeshRenderer, RenderSettings, Shading};
use rasterlab::measure::{find, Contender, Context, Side, Workload, FULL_DRAGON};
use rasterlab::raster::{triangle_backend, RenderTarget};
use std::cell::RefCell;
use std::path::PathBuf;

const W: u32 = 1920;
const H: u32 = 1080;

fn renderer(mesh: &Mesh, zoom: f32, clip: ClipPlanes) -> MeshRenderer {
    let mut settings = RenderSettings {
        width: W,
        height: H,
        azimuth: 30.0,
        zoom,
        shading: Shading::Gouraud,
        ..RenderSettings::default()
    };
    settings.pipeline.cull = CullMode::Back;
    settings.pipeline.clip = clip;
    MeshRenderer::new(mesh, settings).unwrap()
}

fn main() {
    let mut rounds = 10;
    let mut filters = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--rounds" => {
                rounds = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .filter(|n| *n >= 1)
                    .expect("--rounds takes a whole number of at least 1")
            }
            a if a.starts_with("--") => {}
            a => filters.push(a.to_string()),
        }
    }
    let wants = |name: &str| filters.is_empty() || filters.iter().any(|f| name.contains(f));
    let mut context = Context::start(1, rounds, W, H);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let scanline = triangle_backend("scanline").unwrap();
    let bundled = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz");
    let models = [("dragon_res4", Ok(bundled)), ("dragon", find(FULL_DRAGON))];
    for (model, path) in models {
        let views = [("zoom2.5", 2.5), ("inside", 12.0)];
        let names: Vec<String> = views.iter().map(|v| format!("{model}_{}", v.0)).collect();
        if !names.iter().any(|n| wants(n)) {
            continue;
        }
        let mesh = match path {
            Ok(path) => Mesh::load(&path).unwrap(),
            Err(why) => {
                println!("{model}: skipped, {}", why.reason);
                continue;
            }
        };
        for ((_, zoom), name) in views.into_iter().zip(names) {
            if !wants(&name) {
                continue;
            }
            let modes = [ClipPlanes::GuardBand, ClipPlanes::Viewport];
            let renderers = modes.map(|clip| renderer(&mesh, zoom, clip));
            for (clip, r) in modes.iter().zip(&renderers) {
                let target = &mut *target.borrow_mut();
                let stats = one.install(|| r.render_into(scanline, target)).unwrap();
                let g = stats.geometry;
                println!(
                    "{name} --clip {clip}: {} rejected, {} clipped, {} culled, {} with no pixel centre, {} small and covering none, {} rasterized; {} fragments",
                    g.rejected, g.clipped, g.culled, g.empty_bounds, g.no_sample, g.triangles, stats.work.fragments
                );
            }
            let mut work = Workload::new(&name);
            let (one, target) = (&one, &target);
            for (clip, r) in modes.iter().zip(&renderers) {
                work.add(Contender::new(
                    &format!("geometry-{clip}"),
                    Side::Rasterlab,
                    1,
                    move || one.install(|| r.geometry().unwrap().setups.len()),
                ));
                work.add(Contender::new(
                    &format!("frame-{clip}"),
                    Side::Rasterlab,
                    1,
                    move || {
                        let target = &mut *target.borrow_mut();
                        one.install(|| r.render_into(scanline, target).unwrap().work.fragments)
                    },
                ));
            }
            let result = work.run(rounds);
            print!("{}", result.figure_table());
        }
    }
    context.finish();
    println!();
    println!(
        "cargo bench --bench clipping -- --rounds {rounds}{}",
        filters.iter().map(|f| format!(" {f}")).collect::<String>()
    );
    print!("{context}");
}
