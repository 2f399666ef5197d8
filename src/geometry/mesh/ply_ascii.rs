//! The payload of an ASCII PLY file, read line by line.
//!
//! After the header, an ASCII PLY file holds one element per line: its
//! properties' values in the header's order, separated by spaces or tabs,
//! a list as its length and then its values. This reader plans once, per
//! element, where each property's value goes (a position's coordinate, a
//! normal's, a colour channel, a face's indices, or nowhere), then reads
//! each line into the columns of a [`Payload`] without an intermediate
//! value per property: the full Stanford dragon's 1.3 million lines are
//! most of a load's time, and the generic parser spent several times the
//! time of the number parsing itself around it.
//!
//! Every value is checked against its declared type (an integer property
//! takes an integer in its type's range, a float one a number); a line
//! with too few or too many values is an error. Errors give the 1-based
//! line; what the values mean (finite coordinates, indices in range) is
//! checked afterwards, by the caller.
//!
//! Two kinds of line make up nearly all of a scanned mesh: a face whose one
//! property is its list of integer indices, and a vertex whose properties
//! are all floats. They have a plain reading each, without the general
//! reader's dispatch per value ([`plain`]); a line the plain reading does
//! not take whole (a sign, a value out of range, anything wrong) goes to
//! the general reader, which reads it the same way or names what is wrong
//! with it.

mod plain;

use super::ply_blocks::{self, Outcome, ParseLines, Parsing};
use super::ply_payload::{Payload, VertexColumn};
use plain::{read_plain_vertex, PlainFace};
use ply_rs_bw::ply::{ElementDef, PropertyType, ScalarType};
use std::io::BufRead;

/// Where a property's values go.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Slot {
    /// A column of the vertices.
    Vertex(VertexColumn),
    /// A face's vertex indices.
    Indices,
    /// Read, checked and dropped.
    Skip,
}

/// Which element of the mesh a line holds.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// A `vertex` element.
    Vertex,
    /// A `face` element.
    Face,
    /// An element the mesh does not use.
    Other,
}

/// A value's type, as a message names it.
fn type_name(t: &ScalarType) -> &'static str {
    match t {
        ScalarType::Char => "char (-128..=127)",
        ScalarType::UChar => "uchar (0..=255)",
        ScalarType::Short => "short (-32768..=32767)",
        ScalarType::UShort => "ushort (0..=65535)",
        ScalarType::Int => "int (32 bits, signed)",
        ScalarType::UInt => "uint (32 bits, unsigned)",
        ScalarType::Float => "float",
        ScalarType::Double => "double",
    }
}

/// The range of an integer type; `None` for the float types.
fn integer_range(t: &ScalarType) -> Option<(i64, i64)> {
    Some(match t {
        ScalarType::Char => (i8::MIN.into(), i8::MAX.into()),
        ScalarType::UChar => (0, u8::MAX.into()),
        ScalarType::Short => (i16::MIN.into(), i16::MAX.into()),
        ScalarType::UShort => (0, u16::MAX.into()),
        ScalarType::Int => (i32::MIN.into(), i32::MAX.into()),
        ScalarType::UInt => (0, u32::MAX.into()),
        ScalarType::Float | ScalarType::Double => return None,
    })
}

/// Why a line could not be read to its end.
enum Stop {
    /// The slice ended before the line did: read the rest and try again.
    More,
    /// The line is wrong: what is wrong.
    Wrong(String),
}

/// What a value is, as a message names it (put into words only for a
/// message).
#[derive(Copy, Clone)]
enum What<'a> {
    /// The value of the property of this name.
    Value(&'a str),
    /// The length of the list of this name.
    Length(&'a str),
}

impl std::fmt::Display for What<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            What::Value(name) => write!(f, "`{name}`"),
            What::Length(name) => write!(f, "the length of `{name}`"),
        }
    }
}

/// A token as a message quotes it.
fn quoted(token: &[u8]) -> String {
    let text = String::from_utf8_lossy(token);
    let short: String = text.chars().take(40).collect();
    format!("`{short}`")
}

/// Whether `b` separates two values of a line.
#[inline(always)]
fn is_space(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// The decimal integer at the start of `bytes` (an optional sign and at
/// most 18 digits: any value of a PLY integer type fits) and its length;
/// `None` when there is none.
#[inline(always)]
fn parse_integer(bytes: &[u8]) -> Option<(i64, usize)> {
    let (negative, signed) = match bytes.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let mut value = 0i64;
    let mut n = signed;
    while let Some(&d) = bytes.get(n) {
        if !d.is_ascii_digit() {
            break;
        }
        value = value * 10 + i64::from(d - b'0');
        n += 1;
        if n - signed > 18 {
            return None;
        }
    }
    (n > signed).then_some((if negative { -value } else { value }, n))
}

/// The value of type `t` at the start of `bytes`, as `f64` (what the
/// caller stores as `f32`), and its length; `None` when there is none.
#[inline(always)]
fn parse_scalar(bytes: &[u8], t: &ScalarType) -> Option<(f64, usize)> {
    match t {
        ScalarType::Float => fast_float2::parse_partial::<f32, _>(bytes)
            .ok()
            .map(|(v, n)| (f64::from(v), n)),
        ScalarType::Double => fast_float2::parse_partial::<f64, _>(bytes).ok(),
        _ => {
            let (lo, hi) = integer_range(t)?;
            let (v, n) = parse_integer(bytes)?;
            (lo..=hi).contains(&v).then_some((v as f64, n))
        }
    }
}

/// A line being read value by value, from a slice that holds it (up to
/// its line break) or, when not `complete`, perhaps only its beginning.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
    complete: bool,
    /// The element and its number, for messages.
    element: &'a str,
    number: usize,
}

impl<'a> Cursor<'a> {
    /// Skips separators; the next byte, or `None` where the line ends (at
    /// its line break, or at the end of a complete slice).
    #[inline(always)]
    fn next_value(&mut self) -> Result<Option<u8>, Stop> {
        while let Some(&b) = self.bytes.get(self.at) {
            if !is_space(b) {
                return match (b, self.bytes.get(self.at + 1)) {
                    (b'\n', _) | (b'\r', Some(b'\n')) => Ok(None),
                    (b'\r', None) if !self.complete => Err(Stop::More),
                    (b'\r', None) => Ok(None),
                    _ => Ok(Some(b)),
                };
            }
            self.at += 1;
        }
        if self.complete {
            Ok(None)
        } else {
            Err(Stop::More)
        }
    }

    /// The token from `start` to the next separator or line break.
    fn token_from(&self, start: usize) -> &'a [u8] {
        let rest = &self.bytes[start..];
        let end = rest
            .iter()
            .position(|&b| is_space(b) || b == b'\n' || b == b'\r')
            .unwrap_or(rest.len());
        &rest[..end]
    }

    /// Whether a value that ends at `end` is whole there: a separator, a
    /// line break or the end of a complete slice follows it.
    #[inline(always)]
    fn ends_at(&self, end: usize) -> Result<bool, Stop> {
        match self.bytes.get(end) {
            Some(&b) => Ok(is_space(b) || b == b'\n' || b == b'\r'),
            None if self.complete => Ok(true),
            None => Err(Stop::More),
        }
    }

    /// A message about this line.
    fn wrong(&self, message: std::fmt::Arguments<'_>) -> Stop {
        Stop::Wrong(format!("`{}` {}: {message}", self.element, self.number))
    }

    /// The next value, of type `t`, as `f64`; `what` names it in a
    /// message.
    #[inline(always)]
    fn value(&mut self, t: &ScalarType, what: What<'_>) -> Result<f64, Stop> {
        if self.next_value()?.is_none() {
            return Err(self.wrong(format_args!("the line ends before {what}")));
        }
        let start = self.at;
        if let Some((v, n)) = parse_scalar(&self.bytes[start..], t) {
            if n > 0 && self.ends_at(start + n)? {
                self.at = start + n;
                return Ok(v);
            }
        }
        let token = self.token_from(start);
        // A value cut by the end of the slice is read again whole.
        if start + token.len() == self.bytes.len() && !self.complete {
            return Err(Stop::More);
        }
        Err(self.wrong(format_args!(
            "{} is not a valid {} ({what})",
            quoted(token),
            type_name(t)
        )))
    }
}

/// How one element's lines are read: per property, where its values go.
struct Plan<'a> {
    name: &'a str,
    kind: Kind,
    properties: Vec<(Slot, &'a str, &'a PropertyType)>,
    /// For a face element whose one property is its list of indices:
    /// how its common lines are read without the general reader.
    plain_face: Option<PlainFace>,
    /// For a vertex element whose properties are all `float`: its
    /// columns (`None` for a property skipped), read without the general
    /// reader.
    plain_vertex: Option<Vec<Option<VertexColumn>>>,
}

impl Plan<'_> {
    /// Reads the line at the start of `bytes` as element `number` into
    /// `payload`, with `vertex` for the columns of a vertex; returns the
    /// bytes read, its line break included. On [`Stop::More`] the payload
    /// is as it was.
    #[inline(always)]
    fn read_line(
        &self,
        bytes: &[u8],
        complete: bool,
        number: usize,
        vertex: &mut [f64; VertexColumn::COUNT],
        payload: &mut Payload,
    ) -> Result<usize, Stop> {
        if let Some(read) = self
            .plain_face
            .and_then(|face| face.read(bytes, complete, payload))
        {
            return Ok(read);
        }
        if let Some(read) = self
            .plain_vertex
            .as_deref()
            .and_then(|columns| read_plain_vertex(columns, bytes, complete, vertex))
        {
            payload.push_vertex(vertex);
            return Ok(read);
        }
        let mut line = Cursor {
            bytes,
            at: 0,
            complete,
            element: self.name,
            number,
        };
        let had_error = payload.face_error.is_some();
        let read = self.read_values(&mut line, vertex, payload).and_then(|()| {
            match line.next_value()? {
                None => Ok(()),
                Some(_) => Err(line.wrong(format_args!(
                    "{} is more than the header's properties declare",
                    quoted(line.token_from(line.at))
                ))),
            }
        });
        if let Err(stop) = read {
            payload.pending.clear();
            if !had_error {
                payload.face_error = None;
            }
            return Err(stop);
        }
        match self.kind {
            Kind::Vertex => payload.push_vertex(vertex),
            Kind::Face => payload.push_pending_face(),
            Kind::Other => {}
        }
        // Past the line break, if any.
        Ok(bytes[line.at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |k| line.at + k + 1))
    }

    /// The values of a line, where the plan puts them.
    #[inline(always)]
    fn read_values(
        &self,
        line: &mut Cursor<'_>,
        vertex: &mut [f64; VertexColumn::COUNT],
        payload: &mut Payload,
    ) -> Result<(), Stop> {
        for &(slot, name, data_type) in &self.properties {
            match (slot, data_type) {
                (Slot::Vertex(column), PropertyType::Scalar(t)) => {
                    let v = line.value(t, What::Value(name))?;
                    // Colours stored as bytes are 0..=255; as anything
                    // else, 0..=1.
                    vertex[column as usize] = if column.is_color() && *t == ScalarType::UChar {
                        v / 255.0
                    } else {
                        v
                    };
                }
                (Slot::Indices, PropertyType::List(count_type, t)) => {
                    let count = line.value(count_type, What::Length(name))? as usize;
                    let start = payload.pending.len();
                    for _ in 0..count {
                        let index = line.value(t, What::Value(name))?;
                        if (0.0..=f64::from(u32::MAX)).contains(&index) {
                            payload.pending.push(index as u32);
                        } else if payload.face_error.is_none() {
                            payload.face_error = Some((
                                line.number,
                                format!("vertex index {index} is out of range"),
                            ));
                        }
                    }
                    if payload.pending.len() != start + count {
                        payload.pending.truncate(start);
                    }
                }
                (_, PropertyType::Scalar(t)) => {
                    line.value(t, What::Value(name))?;
                }
                (_, PropertyType::List(count_type, t)) => {
                    let count = line.value(count_type, What::Length(name))? as usize;
                    for _ in 0..count {
                        line.value(t, What::Value(name))?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// Reads the `def.count` lines of one element into `payload` (as `kind`
/// says), the first of them at 1-based line `first_line`. An error is the
/// line it is on and what is wrong.
///
/// A large element is read in blocks of lines parsed on several threads
/// when `parsing` says so (see [`super::ply_blocks`]); a small one, or
/// any element on one thread, line by line on this thread. Both give the
/// same payload and the same first error.
pub(super) fn read_element<R: BufRead>(
    reader: &mut R,
    def: &ElementDef,
    kind: Kind,
    first_line: usize,
    payload: &mut Payload,
    parsing: Parsing,
) -> Result<(), (usize, String)> {
    let plan = Plan::new(def, kind, payload);
    // Reserved from the header's count (address space only, see
    // `reserve`).
    plan.reserve(payload, def.count);
    if !parsing.in_blocks(def.count) {
        return read_in_place(reader, &plan, def, first_line, payload);
    }
    match ply_blocks::read(reader, def.count, parsing, payload, &plan) {
        Outcome::Complete => Ok(()),
        Outcome::BadLine(i, message) => Err((first_line + i, message)),
        Outcome::FileEnded(read) => Err(end_of_file(def, first_line, read)),
        Outcome::Failed(read, e) => Err(read_error(def, first_line, read, e)),
        // Nothing was read: this thread reads every line.
        Outcome::NoThreads => read_in_place(reader, &plan, def, first_line, payload),
    }
}

/// The plan parses a block of whole lines for [`ply_blocks`], and the
/// line [`read_in_place`] copies out of a cut buffer.
impl ParseLines for Plan<'_> {
    /// Reads `lines` whole lines from the start of `bytes` (each ends with
    /// a line break, but the last may end with `bytes`), the first of them
    /// element `first`, into `payload`. An error is the element it is in
    /// and what is wrong.
    fn parse(
        &self,
        bytes: &[u8],
        lines: usize,
        first: usize,
        payload: &mut Payload,
    ) -> Result<(), (usize, String)> {
        let mut vertex = [0f64; VertexColumn::COUNT];
        let mut at = 0;
        for i in first..first + lines {
            match self.read_line(&bytes[at..], true, i, &mut vertex, payload) {
                Ok(n) => at += n,
                Err(Stop::More) => unreachable!("a complete line is never cut"),
                Err(Stop::Wrong(m)) => return Err((i, m)),
            }
        }
        Ok(())
    }
}

impl<'a> Plan<'a> {
    /// The plan for element `def`, read as `kind`. A face element whose
    /// indices are not a list of integers gets its error recorded in
    /// `payload` (for its first face).
    fn new(def: &'a ElementDef, kind: Kind, payload: &mut Payload) -> Plan<'a> {
        let properties: Vec<(Slot, &str, &PropertyType)> = def
            .properties
            .values()
            .map(|p| {
                let slot = match (kind, &p.data_type) {
                    (Kind::Vertex, PropertyType::Scalar(_)) => {
                        VertexColumn::of(&p.name).map_or(Slot::Skip, Slot::Vertex)
                    }
                    (Kind::Face, PropertyType::List(..))
                        if p.name == "vertex_indices" || p.name == "vertex_index" =>
                    {
                        Slot::Indices
                    }
                    _ => Slot::Skip,
                };
                (slot, p.name.as_str(), &p.data_type)
            })
            .collect();
        if kind == Kind::Face {
            if let Some((_, name, _)) = properties.iter().find(|(slot, name, _)| {
                *slot == Slot::Skip && (*name == "vertex_indices" || *name == "vertex_index")
            }) {
                payload.face_error = Some((0, format!("`{name}` must be a list of integers")));
            }
        }
        let plain_face = match properties.as_slice() {
            [(Slot::Indices, _, PropertyType::List(count, index))] => PlainFace::new(count, index),
            _ => None,
        };
        let plain_vertex = (kind == Kind::Vertex)
            .then(|| {
                properties
                    .iter()
                    .map(|&(slot, _, data_type)| match (slot, data_type) {
                        (Slot::Vertex(c), PropertyType::Scalar(ScalarType::Float)) => Some(Some(c)),
                        (Slot::Skip, PropertyType::Scalar(ScalarType::Float)) => Some(None),
                        _ => None,
                    })
                    .collect::<Option<Vec<_>>>()
            })
            .flatten();
        Plan {
            name: &def.name,
            kind,
            properties,
            plain_face,
            plain_vertex,
        }
    }

    /// Room in `payload` for `lines` more lines of this element.
    fn reserve(&self, payload: &mut Payload, lines: usize) {
        match self.kind {
            Kind::Vertex => payload.reserve_vertices(lines),
            Kind::Face => payload.reserve_faces(lines),
            Kind::Other => {}
        }
    }
}

/// The error of a file that ends after `read` of the `def.count` lines
/// of element `def`.
fn end_of_file(def: &ElementDef, first_line: usize, read: usize) -> (usize, String) {
    (
        first_line + read,
        format!(
            "unexpected end of file: the header declares {} `{}` elements, the file ends after {read}",
            def.count, def.name
        ),
    )
}

/// The error of a read that failed after `read` lines of element `def`.
fn read_error(
    def: &ElementDef,
    first_line: usize,
    read: usize,
    e: std::io::Error,
) -> (usize, String) {
    (
        first_line + read,
        format!("reading `{}` {read}: {e}", def.name),
    )
}

/// Reads the element line by line on this thread.
///
/// A line is read where the reader's buffer holds it; only a line cut by
/// the end of the buffer is copied out, whole, and read from the copy.
fn read_in_place<R: BufRead>(
    reader: &mut R,
    plan: &Plan<'_>,
    def: &ElementDef,
    first_line: usize,
    payload: &mut Payload,
) -> Result<(), (usize, String)> {
    let mut copy = Vec::new();
    let mut vertex = [0f64; VertexColumn::COUNT];
    let mut i = 0;
    while i < def.count {
        let buffer = reader
            .fill_buf()
            .map_err(|e| read_error(def, first_line, i, e))?;
        if buffer.is_empty() {
            return Err(end_of_file(def, first_line, i));
        }
        // The lines the buffer holds whole, read where they are.
        let mut used = 0;
        let mut cut = false;
        while i < def.count {
            match plan.read_line(&buffer[used..], false, i, &mut vertex, payload) {
                Ok(n) => {
                    used += n;
                    i += 1;
                }
                Err(Stop::More) => {
                    cut = true;
                    break;
                }
                Err(Stop::Wrong(m)) => return Err((first_line + i, m)),
            }
        }
        reader.consume(used);
        if cut {
            // A line cut by the buffer's end, copied out whole (up to the
            // end of the file, if it has no line break).
            copy.clear();
            reader
                .read_until(b'\n', &mut copy)
                .map_err(|e| read_error(def, first_line, i, e))?;
            if copy.is_empty() {
                return Err(end_of_file(def, first_line, i));
            }
            plan.parse(&copy, 1, i, payload)
                .map_err(|(i, m)| (first_line + i, m))?;
            i += 1;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use ply_rs_bw::ply::{Addable, PropertyDef};
    use proptest::prelude::*;

    /// An element of the given properties.
    fn element(name: &str, properties: &[(&str, PropertyType)]) -> ElementDef {
        let mut def = ElementDef::new(name.to_string());
        for (name, data_type) in properties {
            def.properties
                .add(PropertyDef::new(name.to_string(), data_type.clone()));
        }
        def
    }

    /// What reading `line` does: its result (the bytes read, or the
    /// error, `None` for a line not whole yet) and the payload after it.
    fn read(
        plan: &Plan<'_>,
        line: &[u8],
        complete: bool,
    ) -> (Option<Result<usize, String>>, Payload) {
        let mut payload = Payload::default();
        payload.clear_vertices(&element("vertex", &[]));
        let mut vertex = [0f64; VertexColumn::COUNT];
        let result = match plan.read_line(line, complete, 0, &mut vertex, &mut payload) {
            Ok(n) => Some(Ok(n)),
            Err(Stop::More) => None,
            Err(Stop::Wrong(m)) => Some(Err(m)),
        };
        (result, payload)
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(4000, "tests/proptest-regressions/src-geometry-mesh-ply_ascii.txt"))]

        /// The plain readings of faces and vertices read every line as the
        /// general reader does: the same values, the same bytes, the same
        /// error, the same wait for a line not whole.
        #[test]
        fn plain_lines_read_as_the_general_reader_does(
            tokens in prop::collection::vec(prop::sample::select(vec![
                "3", "4", "2", "0", "17", "255", "256", "4294967295", "4294967296",
                "2147483647", "2147483648", "-1", "+2", "007", "1.5", "-0.25e1", "x", "nan",
                "inf", "1e40", "12345678901",
            ]), 0..7),
            separators in prop::collection::vec(prop::sample::select(vec![" ", "\t", "  "]), 7),
            ending in prop::sample::select(vec!["\n", "\r\n", "", " \n", "\r", "\n3 0 1 2\n"]),
            complete in any::<bool>(),
            list in prop::sample::select(vec![
                (ScalarType::UChar, ScalarType::Int),
                (ScalarType::UChar, ScalarType::UInt),
                (ScalarType::Int, ScalarType::UShort),
            ]),
        ) {
            let mut line = String::new();
            for (token, separator) in tokens.iter().zip(&separators) {
                line += separator;
                line += token;
            }
            line += ending;
            let face = element("face", &[("vertex_indices", PropertyType::List(list.0, list.1))]);
            let vertex = element("vertex", &[
                ("x", PropertyType::Scalar(ScalarType::Float)),
                ("confidence", PropertyType::Scalar(ScalarType::Float)),
                ("y", PropertyType::Scalar(ScalarType::Float)),
                ("z", PropertyType::Scalar(ScalarType::Float)),
            ]);
            for (def, kind) in [(&face, Kind::Face), (&vertex, Kind::Vertex)] {
                let plain = Plan::new(def, kind, &mut Payload::default());
                prop_assert!(plain.plain_face.is_some() || plain.plain_vertex.is_some());
                let general = Plan { plain_face: None, plain_vertex: None, ..Plan::new(def, kind, &mut Payload::default()) };
                // Compared as text: a NaN coordinate is not equal to itself.
                prop_assert_eq!(
                    format!("{:?}", read(&plain, line.as_bytes(), complete)),
                    format!("{:?}", read(&general, line.as_bytes(), complete))
                );
            }
        }
    }

    #[test]
    fn values_parse_by_their_declared_type() {
        assert_eq!(parse_integer(b"-128 "), Some((-128, 4)));
        assert_eq!(parse_integer(b"+7"), Some((7, 2)));
        for bad in [&b""[..], b"-", b"x1", b"1234567890123456789"] {
            assert_eq!(parse_integer(bad), None);
        }
        assert_eq!(parse_scalar(b"255", &ScalarType::UChar), Some((255.0, 3)));
        assert_eq!(parse_scalar(b"256", &ScalarType::UChar), None);
        assert_eq!(parse_scalar(b"-1", &ScalarType::UInt), None);
        assert_eq!(parse_scalar(b"-1", &ScalarType::Char), Some((-1.0, 2)));
        assert_eq!(parse_scalar(b"1.5", &ScalarType::Int), Some((1.0, 1)));
        assert_eq!(
            parse_scalar(b"0.1 2", &ScalarType::Float),
            Some((f64::from(0.1f32), 3))
        );
        assert_eq!(parse_scalar(b"0.1", &ScalarType::Double), Some((0.1, 3)));
        assert_eq!(parse_scalar(b"x", &ScalarType::Float), None);
    }
}
