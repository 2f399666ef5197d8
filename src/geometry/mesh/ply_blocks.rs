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
//! into payloads of their own as the line-by-line reader would (its
//! plan, given as [`ParseLines`]). The payloads are appended in the
//! blocks' order, so the result
//! is the same as one thread's, whatever the threads' timing.
//!
//! The first error is the same too: a block stops at its first bad line,
//! and the blocks' results are taken in order, so the error of the
//! earliest bad line wins; a file that ends too early or fails to read
//! is reported only if every line before that point parsed. Reading stops
//! at the first error seen, and at most a few blocks are in flight, so a
//! bad or endless file costs no more time or memory than the lines before
//! its error.

use super::ply_payload::Payload;
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

    /// `threads` threads, blocks of about `block_bytes`, every element.
    #[cfg(test)]
    pub(super) fn blocks_of(threads: usize, block_bytes: usize) -> Parsing {
        Parsing {
            threads,
            block_bytes,
            min_lines: 0,
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

/// How reading an element in blocks ended.
pub(super) enum Outcome {
    /// Every line was read into the payload.
    Complete,
    /// The first bad line: its element's number, and what is wrong.
    BadLine(usize, String),
    /// The file ended after this many lines.
    FileEnded(usize),
    /// Reading failed after this many lines.
    Failed(usize, std::io::Error),
    /// No thread could be started; nothing was read.
    NoThreads,
}

/// Parses `lines` whole lines from the start of the bytes, the first of
/// them element `first`, into the payload; an error is the element of
/// the first bad line and what is wrong with it.
pub(super) trait ParseLines: Sync {
    fn parse(
        &self,
        bytes: &[u8],
        lines: usize,
        first: usize,
        payload: &mut Payload,
    ) -> Result<(), (usize, String)>;
}

/// Reads the next `count` lines of `reader` into `payload`, `lines`
/// parsing each block on the threads `parsing` gives; the payload and
/// the first error are those of parsing every line in order on one
/// thread.
pub(super) fn read<R: BufRead>(
    reader: &mut R,
    count: usize,
    parsing: Parsing,
    payload: &mut Payload,
    lines: &impl ParseLines,
) -> Outcome {
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
                .spawn_scoped(scope, move || parse_blocks(work_queue, lines, &parsed));
            workers += usize::from(spawned.is_ok());
        }
        drop(parsed);
        if workers == 0 {
            drop(work);
            return Outcome::NoThreads;
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
            count,
            parsing.block_bytes,
            &mut joined,
            |block| work.send(block).is_ok(),
            &results,
        );
        drop(work);
        for result in results {
            joined.take(result);
        }
        match (joined.error, end) {
            (Some((i, m)), _) => Outcome::BadLine(i, m),
            (None, End::Complete | End::BadLine) => Outcome::Complete,
            (None, End::FileEnded(read)) => Outcome::FileEnded(read),
            (None, End::Failed(read, e)) => Outcome::Failed(read, e),
        }
    })
}

/// A worker: parses blocks until the queue closes.
fn parse_blocks(
    work_queue: &Mutex<Receiver<Block>>,
    lines: &impl ParseLines,
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
        let result = lines.parse(&block.bytes, block.lines, block.first, &mut block.payload);
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
