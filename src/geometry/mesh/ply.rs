//! PLY meshes (the Stanford scans): ASCII, binary little- or big-endian,
//! optionally gzip-compressed.
//!
//! The header, and the payload of a binary file, are read by the
//! `ply-rs-bw` crate into two small typed element structs. The payload of
//! an ASCII file, most of a large scan's load, is read line by line
//! straight into the mesh's columns (`ply_ascii`), its common lines
//! (faces of plain integers, vertices of floats) without the general
//! reader's dispatch per value; a large element is cut into blocks of
//! lines parsed on several threads (`ply_blocks`); a gzip-compressed
//! file is inflated on a thread of its own while the others parse
//! (`inflate`). The faces are kept as the mesh's triangle array when
//! every one is a triangle, so the mesh takes them without a copy. The
//! 871,414-triangle dragon, 34 MB of text, loads in about the time its
//! decompression takes. Recognised properties: `x y z` (required), `nx ny nz`,
//! `red green blue` (bytes or floats), `u v` / `s t` / `texture_u texture_v`,
//! and the face list `vertex_indices` (or `vertex_index`). Other elements and
//! properties are skipped.
//!
//! **Why not `ply-rs-bw` alone.** Its general reader makes a `String`, a
//! token vector and a dynamically typed property in a map per value, per
//! line; the mesh then has to copy them out, which makes it many times
//! slower than this reader on the same bytes (`cargo bench --bench
//! ply_load` times both; docs/benchmarks.md and the log's entry
//! "2026-12-02, `0751882`: loading, the first frame, and `render` on the
//! fast path" in docs/performance-log.md give the figures). So the crate
//! keeps what it does well, the header and binary payloads, and the ASCII
//! payload is read here.
//!
//! A malformed file is an [`Error::Parse`] with the file and, for ASCII
//! files, the 1-based line: bad headers, short payloads, values that are not
//! numbers, non-finite coordinates, faces with fewer than three vertices and
//! indices out of range all name their line.

use super::inflate::Inflated;
use super::ply_ascii::{self, Kind};
use super::ply_blocks::Parsing;
use super::ply_payload::{Payload, VertexColumn};
use super::Mesh;
use crate::error::{Error, Result};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult,
};
use std::fs::File;
use std::io::{BufRead, BufReader};
use std::path::Path;

/// Reads what is left after the last element: nothing (or, for ASCII,
/// white space). Reading to the end also makes a gzip decoder check every
/// member's CRC and length.
fn check_nothing_follows(mut rest: impl BufRead, ascii: bool) -> std::result::Result<(), String> {
    let mut seen = 0usize;
    loop {
        let chunk = rest
            .fill_buf()
            .map_err(|e| format!("after the last element: {e}"))?;
        if chunk.is_empty() {
            return Ok(());
        }
        if !ascii || chunk.iter().any(|b| !b.is_ascii_whitespace()) {
            return Err(
                "data after the last element the header declares (more faces or vertices than its counts?)"
                    .into(),
            );
        }
        let n = chunk.len();
        seen += n;
        if seen > MAX_TRAILING_BYTES {
            return Err(format!(
                "more than {MAX_TRAILING_BYTES} bytes after the last element"
            ));
        }
        rest.consume(n);
    }
}

/// Loads a PLY file (gzip-compressed when it starts with the gzip magic
/// bytes; every member of a multi-member file is read, and the CRC and
/// length of each are checked, since the whole stream is read to its end).
/// A compressed file is inflated on a second thread while this one parses.
pub fn load_ply(path: &Path) -> Result<Mesh> {
    let mut file = BufReader::new(File::open(path).map_err(|e| Error::io(path, &e))?);
    let gzip = file
        .fill_buf()
        .map_err(|e| Error::io(path, &e))?
        .starts_with(&[0x1f, 0x8b]);
    let threads = rayon::current_num_threads();
    if !gzip {
        return read_parsing(file, path, Parsing::on(threads));
    }
    // Ownership of the file moves to the inflating thread; without a
    // thread it is inflated here as it is read.
    match Inflated::spawn(BufReader::new(
        File::open(path).map_err(|e| Error::io(path, &e))?,
    )) {
        // The inflating thread keeps a core busy: parsing on as many
        // threads as the others (on two cores, line by line beside it) is
        // faster than three threads taking turns on two cores.
        Some(inflated) => read_parsing(inflated, path, Parsing::on(threads.saturating_sub(1))),
        None => read_parsing(
            BufReader::new(flate2::bufread::MultiGzDecoder::new(file)),
            path,
            Parsing::on(threads),
        ),
    }
}

/// The most bytes read after the last element before the file is refused
/// (white space only, for ASCII files): a bound on what a hostile file can
/// make the loader read.
const MAX_TRAILING_BYTES: usize = 1 << 20;

/// Parses PLY data from a reader; `path` is used in error messages only.
///
/// The data must end with the last element the header declares (ASCII
/// files may end with white space): extra faces or bytes are an error, not
/// silently dropped.
///
/// Large ASCII elements are parsed on as many threads as rayon's pool has
/// (the program's `--threads`).
pub fn read_ply<R: BufRead>(source: R, path: &Path) -> Result<Mesh> {
    read_parsing(source, path, Parsing::on(rayon::current_num_threads()))
}

/// [`read_ply`], with the parsing of ASCII elements shared out as `parsing`
/// says.
pub(super) fn read_parsing<R: BufRead>(source: R, path: &Path, parsing: Parsing) -> Result<Mesh> {
    let parse_error = |e: ply_rs_bw::parser::ParseError, ascii: bool| Error::Parse {
        path: path.to_path_buf(),
        line: if ascii { e.line() } else { None },
        message: header_message(&strip_line_prefix(&e.to_string())),
    };
    let mut reader = Reader::new(source);
    let header = Parser::<PlyVertex>::new()
        .read_header(&mut reader)
        .map_err(|e| parse_error(e, true))?;
    let ascii = header.encoding == Encoding::Ascii;
    // The 1-based line of the next payload line (ASCII only).
    let mut next_line = reader.line().max(1);
    let located = |line: usize, message: String| Error::Parse {
        path: path.to_path_buf(),
        line: ascii.then_some(line),
        message,
    };

    let mut payload = Payload::default();
    let (mut vertex_line, mut face_line) = (None, None);
    let mut reader = reader.into_inner();
    for (name, def) in &header.elements {
        let first_line = next_line;
        let kind = match name.as_str() {
            "vertex" => {
                if !["x", "y", "z"]
                    .iter()
                    .all(|p| def.properties.contains_key(*p))
                {
                    return Err(located(first_line, "vertex element lacks x, y or z".into()));
                }
                // A second `vertex` element replaces the first.
                payload.clear_vertices(def);
                vertex_line = Some(first_line);
                Kind::Vertex
            }
            "face" => {
                payload.clear_faces();
                face_line = Some(first_line);
                Kind::Face
            }
            _ => Kind::Other,
        };
        if ascii {
            ply_ascii::read_element(&mut reader, def, kind, first_line, &mut payload, parsing)
                .map_err(|(line, message)| located(line, message))?;
        } else {
            read_binary_element(&mut reader, def, &header, kind, &mut payload)
                .map_err(|e| parse_error(e, false))?;
        }
        next_line += def.count;
    }
    check_nothing_follows(reader, ascii).map_err(|message| located(next_line, message))?;

    let vertex_line =
        vertex_line.ok_or_else(|| located(1, "no `vertex` element in the header".into()))?;
    let face_line =
        face_line.ok_or_else(|| located(1, "no `face` element in the header".into()))?;
    payload.into_mesh(vertex_line, face_line, located)
}

/// Reads one element of a binary file with `ply-rs-bw` into `payload`.
fn read_binary_element<R: BufRead>(
    reader: &mut R,
    def: &ElementDef,
    header: &Header,
    kind: Kind,
    payload: &mut Payload,
) -> std::result::Result<(), ply_rs_bw::parser::ParseError> {
    // The parser keeps no state between elements of a binary file but
    // the reader's position.
    let mut reader = Reader::new(reader);
    match kind {
        Kind::Vertex => {
            let vertices =
                Parser::<PlyVertex>::new().read_payload_for_element(&mut reader, def, header)?;
            payload.reserve_vertices(vertices.len());
            for v in &vertices {
                let mut columns = [0f64; VertexColumn::COUNT];
                for (k, c) in v
                    .position
                    .iter()
                    .chain(&v.normal)
                    .chain(&v.color)
                    .chain(&v.uv)
                    .enumerate()
                {
                    columns[k] = f64::from(*c);
                }
                payload.push_vertex(&columns);
            }
        }
        Kind::Face => {
            let faces =
                Parser::<PlyFace>::new().read_payload_for_element(&mut reader, def, header)?;
            for (i, f) in faces.into_iter().enumerate() {
                if let (Some(message), None) = (f.error, &payload.face_error) {
                    payload.face_error = Some((i, message));
                }
                payload.push_face(&f.indices);
            }
        }
        Kind::Other => {
            Parser::<Skipped>::new().read_payload_for_element(&mut reader, def, header)?;
        }
    }
    Ok(())
}

/// `ply-rs-bw` writes "Line N: message"; the line goes in [`Error::Parse::line`].
fn strip_line_prefix(message: &str) -> String {
    let rest = message
        .strip_prefix("Line ")
        .and_then(|m| m.split_once(": "))
        .map_or(message, |(_, m)| m);
    rest.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// A parser message made readable. `ply-rs-bw` follows some messages
/// with its parser's debug value (" Error: ParseError { .. }"), which is
/// cut; of a file whose first line is not `ply` it says only what it
/// expected, or what it parsed that line as, so that message is
/// rewritten to quote the line; an empty file is said to be empty, and a
/// header that is not UTF-8 not text.
fn header_message(message: &str) -> String {
    let message = message
        .split_once(" Error: ParseError")
        .map_or(message, |(m, _)| m);
    if message.starts_with("Expected magic number 'ply'") {
        let first = message
            .rsplit_once("String: '")
            .map_or("", |(_, line)| line.trim_end_matches('\'').trim());
        return format!("not a PLY file: its first line is `{first}`, not `ply`");
    }
    if message.starts_with("Unexpected end of file while reading magic number") {
        return "not a PLY file: it is empty (a PLY file starts with the line `ply`)".into();
    }
    if message.contains("did not contain valid UTF-8") {
        return "the header is not text: a PLY file's header is ASCII text, a binary file's too"
            .into();
    }
    message.to_string()
}

/// A scalar property as `f64`, whatever its stored type.
fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => f64::from(v),
        Property::UChar(v) => f64::from(v),
        Property::Short(v) => f64::from(v),
        Property::UShort(v) => f64::from(v),
        Property::Int(v) => f64::from(v),
        Property::UInt(v) => f64::from(v),
        Property::Float(v) => f64::from(v),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// One `vertex` element.
#[derive(Default)]
struct PlyVertex {
    position: [f32; 3],
    normal: [f32; 3],
    color: [f32; 3],
    uv: [f32; 2],
    has_normal: bool,
    has_color: bool,
    has_uv: bool,
}

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex::default()
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        let Some(v) = scalar(&property) else {
            return PropertyAccessResult::Ignored;
        };
        // Colours stored as bytes are 0..=255; as floats, 0..=1.
        let colour = if matches!(property, Property::UChar(_)) {
            v / 255.0
        } else {
            v
        };
        let v = v as f32;
        match name {
            "x" => self.position[0] = v,
            "y" => self.position[1] = v,
            "z" => self.position[2] = v,
            "nx" | "ny" | "nz" => {
                self.has_normal = true;
                self.normal[usize::from(name.as_bytes()[1] - b'x')] = v;
            }
            "red" | "green" | "blue" => {
                self.has_color = true;
                let k = ["red", "green", "blue"]
                    .iter()
                    .position(|c| *c == name)
                    .unwrap_or(0);
                self.color[k] = colour as f32;
            }
            "u" | "s" | "texture_u" | "texture_s" => {
                self.has_uv = true;
                self.uv[0] = v;
            }
            "v" | "t" | "texture_v" | "texture_t" => {
                self.has_uv = true;
                self.uv[1] = v;
            }
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

/// One `face` element: its vertex indices, or why they are unusable.
#[derive(Default)]
struct PlyFace {
    indices: Vec<u32>,
    error: Option<String>,
}

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace::default()
    }

    fn set_property(&mut self, name: &str, property: Property) -> PropertyAccessResult {
        if name != "vertex_indices" && name != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        let values: Vec<i64> = match property {
            Property::ListChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUChar(v) => v.into_iter().map(i64::from).collect(),
            Property::ListShort(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUShort(v) => v.into_iter().map(i64::from).collect(),
            Property::ListInt(v) => v.into_iter().map(i64::from).collect(),
            Property::ListUInt(v) => v.into_iter().map(i64::from).collect(),
            _ => {
                self.error = Some(format!("`{name}` must be a list of integers"));
                return PropertyAccessResult::Set;
            }
        };
        match values
            .iter()
            .find(|&&i| !(0..=i64::from(u32::MAX)).contains(&i))
        {
            Some(bad) => self.error = Some(format!("vertex index {bad} is out of range")),
            None => self.indices = values.into_iter().map(|i| i as u32).collect(),
        }
        PropertyAccessResult::Set
    }
}

/// An element of a kind the mesh does not use.
struct Skipped;

impl PropertyAccess for Skipped {
    fn new() -> Self {
        Skipped
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn parse(text: &str) -> Result<Mesh> {
        read_ply(text.as_bytes(), Path::new("t.ply"))
    }

    const HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

    #[test]
    fn reads_an_ascii_triangle() {
        let m = parse(&format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")).unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
        assert_eq!(m.positions[1], Vec3::X);
        assert_eq!(m.normals[0], Vec3::Z);
    }

    fn line_of(text: &str) -> (Option<usize>, String) {
        match parse(text) {
            Err(Error::Parse { line, message, .. }) => (line, message),
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn errors_name_the_line() {
        // Header is 9 lines; vertices on lines 10-12, the face on line 13.
        assert_eq!(
            line_of(&format!("{HEADER}0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n")).0,
            Some(11)
        );
        assert_eq!(
            line_of(&format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n")).0,
            Some(13)
        );
        assert_eq!(
            line_of(&format!("{HEADER}0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n")).0,
            Some(12)
        );
        assert_eq!(
            line_of(&format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n2 0 1\n")).0,
            Some(13)
        );
        assert_eq!(
            line_of(&format!("{HEADER}0 0 0\n1 0 0\n"))
                .0
                .map(|l| l >= 12),
            Some(true)
        );
        assert_eq!(
            line_of("ply\nformat ascii 1.0\nelement vertex three\n").0,
            Some(3)
        );
        assert!(matches!(line_of("not a ply file\n").0, Some(1)));
    }

    #[test]
    fn a_file_ending_early_says_so_on_the_first_missing_line() {
        // Header 9 lines, vertices 0 and 1 on lines 10 and 11: with or
        // without a final line break, vertex 2 (line 12) is missing.
        for payload in ["0 0 0\n1 0 0\n", "0 0 0\n1 0 0"] {
            let (line, message) = line_of(&format!("{HEADER}{payload}"));
            assert_eq!(line, Some(12), "{payload:?}");
            assert!(
                message.starts_with("unexpected end of file: the header declares 3 `vertex`"),
                "{payload:?}: {message}"
            );
        }
    }

    #[test]
    fn a_file_that_is_not_ply_says_so_without_the_parsers_internals() {
        assert_eq!(
            line_of("hello world\nmore\n"),
            (
                Some(1),
                "not a PLY file: its first line is `hello world`, not `ply`".into()
            )
        );
        for (text, first) in [
            ("plyx\n", "plyx"),
            ("format ascii 1.0\nend_header\n", "format ascii 1.0"),
        ] {
            let (line, message) = line_of(text);
            assert_eq!(line, Some(1));
            assert_eq!(
                message,
                format!("not a PLY file: its first line is `{first}`, not `ply`")
            );
        }
        assert_eq!(
            line_of(""),
            (
                None,
                "not a PLY file: it is empty (a PLY file starts with the line `ply`)".into()
            )
        );
        match read_ply(&b"\xff\xfe\x00binary"[..], Path::new("t.ply")) {
            Err(Error::Parse { message, .. }) => {
                assert!(message.starts_with("the header is not text"), "{message}")
            }
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    /// Each element type read from lines cut at every byte: the same
    /// values as from whole lines, and errors on the line they are on.
    #[test]
    fn lines_cut_anywhere_read_the_same() {
        let text = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 255 0 0\r\n1.5 0 -2e-3 0 255 0\n\t0 1 0 0 0 255 \n3 0 1 2\n";
        let whole = read_ply(&text[..], std::path::Path::new("t.ply")).unwrap();
        for chunk in 1..24 {
            let cut = std::io::BufReader::with_capacity(chunk, &text[..]);
            let mesh = read_ply(cut, std::path::Path::new("t.ply")).unwrap();
            assert_eq!(mesh, whole, "chunks of {chunk}");
        }
        assert_eq!(whole.positions[1], glam::Vec3::new(1.5, 0.0, -2e-3));
        assert_eq!(
            whole.colors.as_ref().unwrap()[2],
            glam::Vec4::new(0.0, 0.0, 1.0, 1.0)
        );
        assert_eq!(whole.triangles, vec![[0, 1, 2]]);
        for (bad, line, says) in [
            (
                "0 0 0 255 0 0\n1.5 0 x 0 255 0\n",
                14,
                "`x` is not a valid float (`z`)",
            ),
            ("0 0 0 256 0 0\n", 13, "`256` is not a valid uchar"),
            ("0 0 0 255 0 0\n1 0 0 0 0 0 7\n", 14, "`7` is more than"),
            (
                "0 0 0 255 0 0\n1 0 0 0 0\n",
                14,
                "the line ends before `blue`",
            ),
            (
                "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1\n",
                16,
                "ends before `vertex_indices`",
            ),
            (
                "0 0 0 1 1 1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2.5\n",
                16,
                "`2.5` is not a valid int",
            ),
        ] {
            let start = std::str::from_utf8(text)
                .unwrap()
                .find("end_header\n")
                .unwrap()
                + 11;
            let file = [&text[..start], bad.as_bytes()].concat();
            for chunk in [1, 5, 64] {
                let cut = std::io::BufReader::with_capacity(chunk, &file[..]);
                match read_ply(cut, std::path::Path::new("t.ply")) {
                    Err(crate::error::Error::Parse {
                        line: Some(l),
                        message,
                        ..
                    }) => {
                        assert_eq!(l, line, "{bad:?}: {message}");
                        assert!(message.contains(says), "{bad:?}: {message}");
                    }
                    other => panic!("{bad:?}: {other:?}"),
                }
            }
        }
    }
}

#[cfg(test)]
mod blocks {
    use super::*;
    use proptest::prelude::*;

    /// The mesh, or the error's text, of `text` read as `parsing` says.
    fn outcome(text: &[u8], parsing: Parsing) -> Result<crate::geometry::mesh::Mesh, String> {
        read_parsing(text, Path::new("test.ply"), parsing).map_err(|e| e.to_string())
    }

    /// An ASCII PLY file: `vertices` vertices (with normals and byte
    /// colours when `rich`), faces from `faces` (their indices taken
    /// modulo one more than the vertices, so some are out of range), and
    /// a last element `extra` of one integer per line.
    fn ply_text(vertices: &[[f32; 3]], faces: &[Vec<u32>], rich: bool, extra: usize) -> String {
        let mut text = format!(
            "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
            vertices.len()
        );
        if rich {
            text += "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n";
        }
        text += &format!(
            "element face {}\nproperty list uchar int vertex_indices\nelement flags {extra}\nproperty int flag\nend_header\n",
            faces.len()
        );
        for (i, v) in vertices.iter().enumerate() {
            text += &format!("{} {} {}", v[0], v[1], v[2]);
            if rich {
                text += &format!(" 0 0 1 {} 7 255", i % 256);
            }
            text += "\n";
        }
        let modulus = vertices.len() as u32 + 1;
        for face in faces {
            text += &face.len().to_string();
            for i in face {
                text += &format!(" {}", i % modulus);
            }
            text += "\n";
        }
        for i in 0..extra {
            text += &format!("{i}\n");
        }
        text
    }

    /// One change to a file's text: a line replaced, a line removed, the
    /// text cut, line breaks made `\r\n`, the last line break dropped.
    #[derive(Clone, Debug)]
    enum Damage {
        Replace(prop::sample::Index, &'static str),
        Remove(prop::sample::Index),
        Cut(prop::sample::Index),
        CarriageReturns,
        NoLastLineBreak,
    }

    fn damage() -> impl Strategy<Value = Damage> {
        let line = prop::sample::select(vec![
            "",
            "x",
            "1 2",
            "1 2 3 4 5 6 7",
            "3 0 1",
            "-1 0 0",
            "3 0 1 99999999999",
            "nan 0 0",
            "4 0 1 2 3",
            "2 0 1",
            "0.5 +1 -2e-3",
            "3 0 1 2 x",
            "1e40 0 0",
        ]);
        prop_oneof![
            (any::<prop::sample::Index>(), line).prop_map(|(at, l)| Damage::Replace(at, l)),
            any::<prop::sample::Index>().prop_map(Damage::Remove),
            any::<prop::sample::Index>().prop_map(Damage::Cut),
            Just(Damage::CarriageReturns),
            Just(Damage::NoLastLineBreak),
        ]
    }

    /// `text` with `damage` done to its payload (the header is kept).
    fn damaged(text: &str, damage: &[Damage]) -> Vec<u8> {
        let (header, payload) = text.split_at(text.find("end_header\n").unwrap() + 11);
        let mut lines: Vec<String> = payload.lines().map(String::from).collect();
        let (mut crlf, mut last_break, mut cut) = (false, true, None);
        for d in damage {
            match d {
                Damage::Replace(at, l) if !lines.is_empty() => {
                    let at = at.index(lines.len());
                    lines[at] = l.to_string();
                }
                Damage::Remove(at) if !lines.is_empty() => {
                    lines.remove(at.index(lines.len()));
                }
                Damage::Cut(at) => cut = Some(*at),
                Damage::CarriageReturns => crlf = true,
                Damage::NoLastLineBreak => last_break = false,
                _ => {}
            }
        }
        let mut payload = lines.join(if crlf { "\r\n" } else { "\n" });
        if last_break && !lines.is_empty() {
            payload += if crlf { "\r\n" } else { "\n" };
        }
        if let Some(at) = cut {
            payload.truncate(at.index(payload.len() + 1));
        }
        [header.as_bytes(), payload.as_bytes()].concat()
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(600, "tests/proptest-regressions/src-geometry-mesh-ply.txt"))]

        /// Blocks of any size, on two to four threads, read every file,
        /// whole or damaged, into the same mesh or the same first error
        /// as one thread reading line by line.
        #[test]
        fn blocks_read_as_one_thread_does(
            vertices in prop::collection::vec(prop::array::uniform3(-1e3f32..1e3), 3..40),
            faces in prop::collection::vec(prop::collection::vec(0u32..60, 3..6), 1..60),
            rich in any::<bool>(),
            extra in 0usize..20,
            damage in prop::collection::vec(damage(), 0..3),
            threads in 2usize..5,
            block_bytes in prop_oneof![Just(1usize), 2usize..200],
        ) {
            let text = damaged(&ply_text(&vertices, &faces, rich, extra), &damage);
            let alone = outcome(&text, Parsing::on(1));
            let shared = outcome(&text, Parsing::blocks_of(threads, block_bytes));
            prop_assert_eq!(shared, alone);
        }
    }

    /// A mesh of 80,000 faces, large enough for the default blocks: the
    /// same mesh on one, two and three threads, and the same error for a
    /// bad line near its end.
    #[test]
    fn a_large_mesh_reads_the_same_on_any_number_of_threads() {
        let n = 200;
        let vertices: Vec<[f32; 3]> = (0..n * n)
            .map(|i| [(i % n) as f32 * 0.1, (i / n) as f32 * 0.01, 0.5])
            .collect();
        let faces: Vec<Vec<u32>> = (0..n - 1)
            .flat_map(|y| (0..n - 1).map(move |x| (y * n + x) as u32))
            .flat_map(|k| {
                [
                    vec![k, k + 1, k + n as u32],
                    vec![k + 1, k + n as u32 + 1, k + n as u32],
                ]
            })
            .collect();
        let text = ply_text(&vertices, &faces, false, 0);
        assert!(Parsing::on(2).in_blocks(faces.len()));
        let alone = outcome(text.as_bytes(), Parsing::on(1));
        assert_eq!(alone.as_ref().map(|m| m.triangles.len()), Ok(faces.len()));
        for threads in [2, 3] {
            assert!(outcome(text.as_bytes(), Parsing::on(threads)) == alone);
        }
        let near_end = text[..text.len() - 200].rfind('\n').unwrap() + 1;
        let line_end = near_end + text[near_end..].find('\n').unwrap();
        let bad = [&text[..near_end], "3 0 1 x", &text[line_end..]]
            .concat()
            .into_bytes();
        let alone = outcome(&bad, Parsing::on(1));
        assert!(
            alone
                .as_ref()
                .is_err_and(|e| e.contains("`x` is not a valid int")),
            "{alone:?}"
        );
        assert_eq!(outcome(&bad, Parsing::on(3)), alone);
    }
}
