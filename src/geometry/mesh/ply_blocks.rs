//! A large ASCII element read in blocks of lines, parsed on several
//! threads at once.
//!
//! Parsing the text is most of a large scan's load (the full dragon's
//! 1.3 million lines), and every line is independent of the others: its
//! element's number is its place among the lines, and what it holds goes
//! to the end of the payload's columns. So this thread only cuts the text
//! into blocks of whole lines (about [`BLOCK_BYTES`] each; counting line
//! breaks is the only look it takes at them), numbers each block's first
//! line, and hands the blocks to worker threads, which parse them
//! into payloads of their own with the same [`Plan`] as the line-by-line
//! reader. The payloads are appended in the blocks' order, so the result
//! is the same as one thread's, whatever the threads' timing.
//!
//! The first error is the same too: a block stops at its first bad line,
//! and the blocks' results are taken in order, so the error of the
//! earliest bad line wins; a file that ends too early or fails to read
//! is reported only if every line before that point parsed. Reading stops
//! at the first error seen, and at most a few blocks are in flight, so a
//! bad or endless file costs no more time or memory than the lines before
//! its error.

use super::ply_ascii::{end_of_file, read_error, read_in_place, Plan};
use super::ply_payload::Payload;
use ply_rs_bw::ply::ElementDef;
use std::collections::BTreeMap;
use std::io::BufRead;
use std::sync::mpsc::{channel, sync_channel, Receiver};
use std::sync::Mutex;

/// The bytes of text in one block, about: large enough that handing a
/// block over costs nothing next to parsing it (about 10,000 lines of
/// the dragon), small enough that the few blocks in flight stay in the
/// cache and come from memory the allocator reuses (a fresh megabyte
/// costs about a millisecond of the kernel zeroing its pages).
pub(super) const BLOCK_BYTES: usize = 256 * 1024;

/// Elements with fewer lines are read on the calling thread.
pub(super) const MIN_LINES: usize = 1 << 15;

/// How the lines of an ASCII element are parsed: on how many threads, in
/// blocks of how many bytes, from how many lines on.
#[derive(Copy, Clone, Debug)]
pub(super) struct Parsing {
    threads: usize,
    block_bytes: usize,
    min_lines: usize,
}

impl Parsing {
    /// On `threads` threads, in blocks of about [`BLOCK_BYTES`], elements
    /// of at least [`MIN_LINES`] lines; one thread (or none) reads every
    /// element line by line on the caller's.
    pub(super) fn on(threads: usize) -> Parsing {
        Parsing {
            threads,
            block_bytes: BLOCK_BYTES,
            min_lines: MIN_LINES,
        }
    }

    /// Whether an element of `lines` lines is read in blocks.
    pub(super) fn in_blocks(&self, lines: usize) -> bool {
        self.threads > 1 && lines >= self.min_lines
    }
}

/// Whole lines of an element, the first of them element `first`, and
/// the payload they are parsed into. Blocks go back and forth between
/// this thread and the workers, so their memory is reused, not faulted
/// in afresh block after block.
struct Block {
    sequence: usize,
    first: usize,
    lines: usize,
    bytes: Vec<u8>,
    payload: Payload,
}

/// A block parsed, and its first error (the element's number and what is
/// wrong), if any.
type Parsed = (Block, Result<(), (usize, String)>);

/// Why reading the element's text stopped.
enum End {
    /// Every line was read.
    Complete,
    /// The file ended after this many lines.
    FileEnded(usize),
    /// Reading failed after this many lines.
    Failed(usize, std::io::Error),
    /// A block had a bad line: nothing more is worth reading.
    BadLine,
}

/// Reads the `def.count` lines of `def` into `payload` on the threads
/// `parsing` gives; the result is the line-by-line reader's.
pub(super) fn read<R: BufRead>(
    reader: &mut R,
    plan: &Plan<'_>,
    def: &ElementDef,
    first_line: usize,
    payload: &mut Payload,
    parsing: Parsing,
) -> Result<(), (usize, String)> {
    let threads = parsing.threads;
    let (work, work_queue) = sync_channel::<Block>(threads);
    let work_queue = Mutex::new(work_queue);
    std::thread::scope(|scope| {
        let (parsed, results) = channel::<Parsed>();
        let mut workers = 0;
        for _ in 0..threads {
            let (work_queue, parsed) = (&work_queue, parsed.clone());
            let spawned = std::thread::Builder::new()
                .name("ply-parse".into())
                .spawn_scoped(scope, move || parse_blocks(work_queue, plan, &parsed));
            workers += usize::from(spawned.is_ok());
        }
        drop(parsed);
        if workers == 0 {
            // No thread could be started: this one reads every line.
            drop(work);
            return read_in_place(reader, plan, def, first_line, payload);
        }
        let mut joined = Joined {
            template: payload.empty_like(),
            payload,
            next: 0,
            waiting: BTreeMap::new(),
            error: None,
            spare: Vec::new(),
        };
        let end = cut_blocks(
            reader,
            def.count,
            parsing.block_bytes,
            &mut joined,
            |block| work.send(block).is_ok(),
            &results,
        );
        drop(work);
        for result in results {
            joined.take(result);
        }
        let read = match end {
            End::Complete | End::BadLine => None,
            End::FileEnded(read) => Some(end_of_file(def, first_line, read)),
            End::Failed(read, e) => Some(read_error(def, first_line, read, e)),
        };
        match (joined.error, read) {
            (Some((i, m)), _) => Err((first_line + i, m)),
            (None, Some(error)) => Err(error),
            (None, None) => Ok(()),
        }
    })
}

/// A worker: parses blocks until the queue closes.
fn parse_blocks(
    work_queue: &Mutex<Receiver<Block>>,
    plan: &Plan<'_>,
    parsed: &std::sync::mpsc::Sender<Parsed>,
) {
    loop {
        // The lock is held only to take a block.
        let Ok(mut block) = work_queue
            .lock()
            .map_err(drop)
            .and_then(|q| q.recv().map_err(drop))
        else {
            return;
        };
        plan.reserve(&mut block.payload, block.lines);
        let result = plan.read_lines(&block.bytes, block.lines, block.first, &mut block.payload);
        if parsed.send((block, result)).is_err() {
            return;
        }
    }
}

/// The blocks' payloads appended in order as they come in.
struct Joined<'a> {
    payload: &'a mut Payload,
    /// An empty payload with the element's columns.
    template: Payload,
    /// The sequence number of the block to append next.
    next: usize,
    /// Blocks parsed ahead of the next one.
    waiting: BTreeMap<usize, Parsed>,
    /// The first bad line, once the blocks before it are appended.
    error: Option<(usize, String)>,
    /// Blocks to fill again.
    spare: Vec<Block>,
}

impl Joined<'_> {
    /// Takes one parsed block, and appends every block now in order.
    fn take(&mut self, parsed: Parsed) {
        self.waiting.insert(parsed.0.sequence, parsed);
        while let Some((mut block, result)) = self.waiting.remove(&self.next) {
            self.next += 1;
            match result {
                _ if self.error.is_some() => {}
                Ok(()) => self.payload.append(&block.payload),
                Err(error) => self.error = Some(error),
            }
            block.payload.clear();
            self.spare.push(block);
        }
    }

    /// An emptied block's buffers, or new ones for blocks of about
    /// `block_bytes`.
    fn spare_buffers(&mut self, block_bytes: usize) -> (Vec<u8>, Payload) {
        match self.spare.pop() {
            Some(block) => (block.bytes, block.payload),
            None => (
                Vec::with_capacity(block_bytes + block_bytes / 4),
                self.template.empty_like(),
            ),
        }
    }
}

/// Cuts the text of `count` lines from `reader` into blocks of whole
/// lines and `send`s them, numbered, taking in the parsed blocks from
/// `results` as it goes; stops early at a bad line. Consumes exactly the
/// element's lines from `reader`, so the next element starts where it
/// left off.
fn cut_blocks<R: BufRead>(
    reader: &mut R,
    count: usize,
    block_bytes: usize,
    joined: &mut Joined<'_>,
    mut send: impl FnMut(Block) -> bool,
    results: &Receiver<Parsed>,
) -> End {
    // Lines counted so far (each has its line break in a block), and
    // lines already sent.
    let (mut lines, mut sent) = (0, 0);
    let mut sequence = 0;
    let mut bytes: Vec<u8> = Vec::with_capacity(block_bytes + block_bytes / 4);
    // `bytes[..line_end]` are whole lines; what follows, a line begun.
    let mut line_end = 0;
    let end = loop {
        while let Ok(result) = results.try_recv() {
            joined.take(result);
        }
        if joined.error.is_some() {
            break End::BadLine;
        }
        if lines == count {
            break End::Complete;
        }
        let buffer = match reader.fill_buf() {
            Ok(buffer) => buffer,
            Err(e) => break End::Failed(lines, e),
        };
        if buffer.is_empty() {
            // A last line without a line break is a line all the same.
            if bytes.len() > line_end {
                lines += 1;
                line_end = bytes.len();
            }
            break if lines == count {
                End::Complete
            } else {
                End::FileEnded(lines)
            };
        }
        // Up to the line break that ends the element's last line.
        let wanted = count - lines;
        let (mut found, mut last_break) = (0, None);
        for at in memchr::memchr_iter(b'\n', buffer).take(wanted) {
            found += 1;
            last_break = Some(at);
        }
        let taken = match last_break {
            Some(at) if found == wanted => at + 1,
            _ => buffer.len(),
        };
        if let Some(at) = last_break {
            lines += found;
            line_end = bytes.len() + at + 1;
        }
        bytes.extend_from_slice(&buffer[..taken]);
        reader.consume(taken);
        if line_end >= block_bytes {
            let (next, payload) = joined.spare_buffers(block_bytes);
            let (block, rest) = split_off_lines(bytes, line_end, next);
            bytes = rest;
            line_end = 0;
            if !send(Block {
                sequence,
                first: sent,
                lines: lines - sent,
                bytes: block,
                payload,
            }) {
                break workers_gone(sent);
            }
            sequence += 1;
            sent = lines;
        }
    };
    if lines > sent && !matches!(end, End::BadLine) {
        bytes.truncate(line_end);
        let (_, payload) = joined.spare_buffers(block_bytes);
        if !send(Block {
            sequence,
            first: sent,
            lines: lines - sent,
            bytes,
            payload,
        }) {
            return workers_gone(sent);
        }
    }
    end
}

/// The end of a read whose workers have all stopped (only a panic, which
/// the thread scope passes on, stops one): the lines sent were not all
/// parsed, so the payload is not whole.
fn workers_gone(sent: usize) -> End {
    End::Failed(
        sent,
        std::io::Error::other("the threads parsing the file stopped"),
    )
}

/// Splits `bytes` after its whole lines, `bytes[..line_end]`: those stay
/// in `bytes`, and the line begun after them moves to `next`, emptied
/// first.
fn split_off_lines(bytes: Vec<u8>, line_end: usize, mut next: Vec<u8>) -> (Vec<u8>, Vec<u8>) {
    next.clear();
    next.extend_from_slice(&bytes[line_end..]);
    let mut bytes = bytes;
    bytes.truncate(line_end);
    (bytes, next)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh::ply::read_parsing;
    use proptest::prelude::*;
    use std::path::Path;

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
        #![proptest_config(ProptestConfig::with_cases(600))]

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
            let shared = outcome(&text, Parsing { threads, block_bytes, min_lines: 0 });
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
