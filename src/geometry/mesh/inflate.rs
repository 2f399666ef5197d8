//! Gzip decompression on a second thread, while the caller parses.
//!
//! Loading a compressed mesh is two chains of work: inflating the bytes
//! and parsing the text. Each is serial, but they need not wait for one
//! another: [`Inflated`] inflates the file on a thread of its own, in
//! chunks handed over through a bounded channel, and the parser reads
//! them as a [`BufRead`]. The load then takes about as long as the slower
//! of the two chains instead of their sum. The chunks go back to the
//! inflating thread once read, so the load touches a few chunks of memory,
//! not a fresh buffer per chunk.
//!
//! Every member of a multi-member file is inflated, and each member's CRC
//! and length are checked (`flate2`'s `MultiGzDecoder`, on the `zlib-rs`
//! back-end); a decompression error reaches the reader as the `io::Error`
//! it is, at the point of the stream where it happened.

use std::io::{self, BufRead, Read};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};

/// Bytes in one chunk: large enough that handing a chunk over costs
/// nothing next to inflating it, small enough to be read while it is
/// still in the cache.
const CHUNK: usize = 256 * 1024;

/// Chunks inflated ahead of the reader, at most.
const AHEAD: usize = 4;

/// The inflated bytes of a gzip stream, read while a second thread
/// inflates the rest.
pub(super) struct Inflated {
    /// Inflated chunks, or the error that ended the stream.
    full: Receiver<io::Result<Vec<u8>>>,
    /// Chunks read, going back to be filled again.
    empty: SyncSender<Vec<u8>>,
    /// The chunk being read, and how far.
    chunk: Vec<u8>,
    at: usize,
}

impl Inflated {
    /// Starts inflating `compressed` on a new thread; `None` if no thread
    /// could be started (the caller then inflates as it reads).
    pub(super) fn spawn<R: BufRead + Send + 'static>(compressed: R) -> Option<Inflated> {
        let (full_tx, full) = sync_channel(AHEAD);
        let (empty, empty_rx) = sync_channel::<Vec<u8>>(AHEAD + 2);
        std::thread::Builder::new()
            .name("inflate".into())
            .spawn(move || {
                let mut decoder = flate2::bufread::MultiGzDecoder::new(compressed);
                loop {
                    let mut chunk = empty_rx.try_recv().unwrap_or_default();
                    chunk.resize(CHUNK, 0);
                    let (n, error) = fill(&mut decoder, &mut chunk);
                    chunk.truncate(n);
                    // The bytes inflated before an error go first, so the
                    // reader reaches the error where the stream broke; an
                    // empty chunk is the end of the stream. A failed send
                    // means the reader has gone (it stopped at an error
                    // of its own): nothing more to do.
                    let last = n == 0 || error.is_some();
                    if (n > 0 || error.is_none()) && full_tx.send(Ok(chunk)).is_err() {
                        return;
                    }
                    if let Some(e) = error {
                        let _ = full_tx.send(Err(damaged(e)));
                    }
                    if last {
                        return;
                    }
                }
            })
            .ok()?;
        Some(Inflated {
            full,
            empty,
            chunk: Vec::new(),
            at: 0,
        })
    }
}

/// Reads from `source` until `buffer` is full or the stream ends; the
/// bytes read, and the error that stopped it early, if one did.
fn fill(source: &mut impl Read, buffer: &mut [u8]) -> (usize, Option<io::Error>) {
    let mut n = 0;
    while n < buffer.len() {
        match source.read(&mut buffer[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return (n, Some(e)),
        }
    }
    (n, None)
}

/// The decoder's error, saying what it means for the file: its
/// compressed data ends early or is damaged.
fn damaged(e: io::Error) -> io::Error {
    io::Error::new(
        e.kind(),
        format!("the gzip data is cut short or damaged ({e})"),
    )
}

impl BufRead for Inflated {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        if self.at == self.chunk.len() {
            // The stream has ended (or failed) once the sender is gone.
            let Ok(next) = self.full.recv() else {
                return Ok(&[]);
            };
            let read = std::mem::replace(&mut self.chunk, next?);
            self.at = 0;
            // The inflating thread makes a new chunk when none comes back.
            let _ = self.empty.try_send(read);
        }
        Ok(&self.chunk[self.at..])
    }

    fn consume(&mut self, amount: usize) {
        self.at = (self.at + amount).min(self.chunk.len());
    }
}

impl Read for Inflated {
    fn read(&mut self, out: &mut [u8]) -> io::Result<usize> {
        let available = self.fill_buf()?;
        let n = available.len().min(out.len());
        out[..n].copy_from_slice(&available[..n]);
        self.consume(n);
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn gzip(bytes: &[u8]) -> Vec<u8> {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(bytes).unwrap();
        e.finish().unwrap()
    }

    /// Several chunks, two members: the same bytes as inflating in place;
    /// a damaged stream ends in the decoder's error.
    #[test]
    fn reads_every_member_in_chunks_and_passes_errors_on() {
        let text: Vec<u8> = (0..3 * CHUNK + 17).map(|i| (i * 7 % 251) as u8).collect();
        let (a, b) = text.split_at(CHUNK + 5);
        let packed = [gzip(a), gzip(b)].concat();
        let mut inflated = Inflated::spawn(io::Cursor::new(packed.clone())).unwrap();
        let mut out = Vec::new();
        inflated.read_to_end(&mut out).unwrap();
        assert!(out == text);
        let mut bad = packed;
        let at = bad.len() - 6;
        bad[at] ^= 0xff;
        let mut inflated = Inflated::spawn(io::Cursor::new(bad)).unwrap();
        let err = inflated.read_to_end(&mut Vec::new()).unwrap_err();
        assert!(err.to_string().contains("checksum"), "{err}");
    }

    /// A stream cut short gives every byte inflated before the cut, as
    /// inflating in place does, then an error that says so.
    #[test]
    fn a_stream_cut_short_gives_what_came_before_the_cut() {
        let text: Vec<u8> = (0..3 * CHUNK)
            .map(|i| b"0123456789 \n"[i * 7 % 12])
            .collect();
        let packed = gzip(&text);
        for cut in [packed.len() / 3, packed.len() - 20] {
            let cut_short = &packed[..cut];
            let mut in_place = flate2::bufread::MultiGzDecoder::new(cut_short);
            let mut expected = vec![0; text.len()];
            let (n, _) = fill(&mut in_place, &mut expected);
            let mut inflated = Inflated::spawn(io::Cursor::new(cut_short.to_vec())).unwrap();
            let mut out = Vec::new();
            let err = loop {
                match inflated.fill_buf() {
                    Ok([]) => panic!("the stream ended without an error"),
                    Ok(bytes) => {
                        let k = bytes.len();
                        out.extend_from_slice(bytes);
                        inflated.consume(k);
                    }
                    Err(e) => break e,
                }
            };
            assert!(
                n > 0 && out == expected[..n],
                "cut at {cut}: {} of {n} bytes",
                out.len()
            );
            assert!(err.to_string().contains("cut short"), "{err}");
        }
    }
}
