//! Writing output files safely: checked before the work, written whole.
//!
//! Every file rasterlab writes (PNG and SVG pictures, reports, benchmark
//! results) goes through [`write_file`]: the bytes go to a temporary file
//! beside the destination, which is then renamed over it, so a failure
//! never leaves a truncated or empty file behind. Commands call
//! [`check_file`] or [`check_dir`] before they start, so a path that cannot
//! be written is reported at once, not after minutes of work.
//!
//! ```
//! use rasterlab::{check_file, write_file};
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("picture.svg");
//! check_file(&path, &["svg"]).unwrap();
//! write_file(&path, b"<svg/>").unwrap();
//! assert_eq!(std::fs::read(&path).unwrap(), b"<svg/>");
//! assert!(check_file(&dir.path().join("x.jpg"), &["svg", "png"]).is_err());
//! ```

use crate::error::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// The file's extension, lower-cased (`"png"` for `A.PNG`).
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// True for an existing path that is neither a file nor a directory: a
/// device such as `/dev/null`, or a pipe. Such a path is written in place
/// (renaming over it would replace the device).
fn is_special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Checks, before any work, that `path` has one of `extensions` (compared
/// without case) and that its folder exists and accepts a new file. A
/// device or pipe (`/dev/null`, `/dev/stdout`) is accepted whatever its
/// name, if it opens for writing.
pub fn check_file(path: &Path, extensions: &[&str]) -> Result<()> {
    if is_special(path) {
        return std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map(drop)
            .map_err(|e| Error::write(path, &e));
    }
    let ext = extension(path);
    if !extensions.iter().any(|e| ext.as_deref() == Some(e)) {
        return Err(Error::Write {
            path: path.to_path_buf(),
            message: format!("this file is written as .{}", extensions.join(" or .")),
            closed: false,
        });
    }
    if path.is_dir() {
        return Err(Error::Write {
            path: path.to_path_buf(),
            message: "it is a directory".into(),
            closed: false,
        });
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    probe_dir(&parent)
}

/// Creates `dir` (and its parents) if needed and checks that it accepts a
/// new file, before any work.
pub fn check_dir(dir: &Path) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        return Err(Error::Write {
            path: dir.to_path_buf(),
            message: "it is a file, and this output is a directory of several files: \
                      name a directory (new or existing)"
                .into(),
            closed: false,
        });
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::write(dir, &e))?;
    probe_dir(dir)
}

/// Creates and removes a temporary file in `dir`.
fn probe_dir(dir: &Path) -> Result<()> {
    if !dir.is_dir() {
        return Err(Error::Write {
            path: dir.to_path_buf(),
            message: "no such directory".into(),
            closed: false,
        });
    }
    let probe = temporary_path(&dir.join("probe"));
    std::fs::File::create(&probe).map_err(|e| Error::write(dir, &e))?;
    std::fs::remove_file(&probe).map_err(|e| Error::write(dir, &e))
}

/// A hidden temporary name beside `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `bytes` to `path` whole or not at all: a temporary file beside it,
/// flushed, then renamed over `path`. A device or pipe is written in place.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    if is_special(path) {
        return std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .and_then(|mut f| f.write_all(bytes))
            .map_err(|e| Error::write(path, &e));
    }
    let temporary = temporary_path(path);
    let written = std::fs::File::create(&temporary).and_then(|mut f| {
        f.write_all(bytes)?;
        f.sync_all()
    });
    let result = written.and_then(|()| std::fs::rename(&temporary, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&temporary);
        return Err(Error::write(path, &e));
    }
    Ok(())
}

/// Writes an RGBA8 image as a PNG file (through [`write_file`]), with the
/// `sRGB` chunk that says its colours are sRGB-encoded, as every colour
/// rasterlab stores is (see [`MixSpace`](crate::raster::MixSpace)): a
/// viewer then shows them as they are meant, without guessing.
pub fn write_png(path: &Path, image: &image::RgbaImage) -> Result<()> {
    let failed = |e: png::EncodingError| Error::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
        closed: false,
    };
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, image.width(), image.height());
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    // `image`'s `write_to` compresses this fast (fdeflate): a frame's PNG
    // costs a tenth of what the default level does, for files about twice
    // as large.
    encoder.set_compression(png::Compression::Fast);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(failed)?;
    writer.write_image_data(image.as_raw()).map_err(failed)?;
    writer.finish().map_err(failed)?;
    write_file(path, &bytes)
}

/// The font pictures' text is drawn with when an SVG becomes a PNG
/// (DejaVu Sans, bundled in `assets/fonts` with its licence), so a
/// picture looks the same on any machine.
#[cfg(feature = "png-text")]
const FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// An SVG picture (a chart, a labelled grid) drawn as an image by
/// `resvg`, its text in the bundled font; `None` when the SVG cannot be
/// read or is empty. Only with the `png-text` feature (on by default).
#[cfg(feature = "png-text")]
pub fn svg_to_png(svg: &str) -> Option<image::RgbaImage> {
    let mut options = resvg::usvg::Options::default();
    options.fontdb_mut().load_font_data(FONT.to_vec());
    options.font_family = "DejaVu Sans".into();
    let tree = resvg::usvg::Tree::from_str(svg, &options).ok()?;
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height())?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    // Pictures have an opaque background, so premultiplied and straight
    // RGBA agree.
    image::RgbaImage::from_raw(size.width(), size.height(), pixmap.take())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_no_file_behind() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        // A path inside a missing folder: the write fails and nothing is left.
        let path = dir.join("missing").join("x.png");
        assert!(matches!(
            write_file(&path, b"data"),
            Err(Error::Write { .. })
        ));
        assert!(!path.exists());
        assert!(check_file(&path, &["png"]).is_err());
        // Upper-case extensions are accepted.
        check_file(&dir.join("X.PNG"), &["png"]).unwrap();
        assert!(check_file(&dir.join("x.jpg"), &["png"]).is_err());
        assert!(check_file(dir, &["png"]).is_err());
        // A file where a folder is asked for says so.
        let file = dir.join("a-file");
        std::fs::write(&file, b"").unwrap();
        match check_dir(&file) {
            Err(Error::Write { message, .. }) => assert!(message.contains("name a directory")),
            other => panic!("expected a write error, got {other:?}"),
        }
        std::fs::remove_file(&file).unwrap();
        assert_eq!(std::fs::read_dir(dir).unwrap().count(), 0, "probes removed");
        // A device is written in place, not replaced.
        check_file(Path::new("/dev/null"), &["png"]).unwrap();
        write_file(Path::new("/dev/null"), b"data").unwrap();
        assert!(is_special(Path::new("/dev/null")));
    }
}
