//! Buffered input shared by all readers: one growable buffer serving lines (text formats and
//! the PLY header) and fixed-size byte records (binary bodies), with the absolute byte offset
//! and, when known, the total size (to cap reservations made from untrusted header counts).

use std::io::{self, Read};

use crate::error::{Location, ReadError, ReadErrorKind};

const CHUNK: usize = 1 << 18;

/// Reservation cap when the input size is unknown: growth beyond it is paid for by real data.
const UNKNOWN_SIZE_RESERVE: u64 = 1 << 16;

pub(crate) struct Input<R> {
    inner: R,
    buf: Vec<u8>,
    pos: usize,
    end: usize,
    /// Absolute offset of `buf[0]`.
    base: u64,
    eof: bool,
    size: Option<u64>,
}

impl<R: Read> Input<R> {
    pub(crate) fn new(inner: R, size: Option<u64>) -> Self {
        Self {
            inner,
            buf: vec![0; CHUNK],
            pos: 0,
            end: 0,
            base: 0,
            eof: false,
            size,
        }
    }

    /// Absolute offset of the next unread byte.
    pub(crate) fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    pub(crate) fn byte_location(&self) -> Location {
        Location::Byte(self.offset())
    }

    /// Bytes left in the input, when its size is known.
    pub(crate) fn remaining(&self) -> Option<u64> {
        self.size.map(|s| s.saturating_sub(self.offset()))
    }

    /// How many items to reserve for `count` announced items of at least `min_bytes` each:
    /// never more than the remaining input can hold, and a small cap when its size is unknown.
    pub(crate) fn reservation(&self, count: u64, min_bytes: u64) -> usize {
        let cap = match self.remaining() {
            Some(r) => r / min_bytes.max(1),
            None => UNKNOWN_SIZE_RESERVE,
        };
        usize::try_from(count.min(cap)).unwrap_or(0)
    }

    /// Buffers at least `n` bytes unless the input ends first; returns how many are buffered.
    pub(crate) fn fill_to(&mut self, n: usize) -> io::Result<usize> {
        while self.end - self.pos < n && !self.eof {
            if self.pos > 0 {
                self.buf.copy_within(self.pos..self.end, 0);
                self.base += self.pos as u64;
                self.end -= self.pos;
                self.pos = 0;
            }
            if self.buf.len() - self.end < CHUNK.min(n) {
                let want = (self.end + n.max(CHUNK)).max(self.buf.len() * 2);
                self.buf.resize(want, 0);
            }
            match self.inner.read(&mut self.buf[self.end..]) {
                Ok(0) => self.eof = true,
                Ok(k) => self.end += k,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        Ok(self.end - self.pos)
    }

    /// Up to `n` upcoming bytes, without consuming them.
    pub(crate) fn peek(&mut self, n: usize) -> io::Result<&[u8]> {
        let k = self.fill_to(n)?.min(n);
        Ok(&self.buf[self.pos..self.pos + k])
    }

    /// The next `n` bytes, or `None` when fewer remain. `n` must be small (a record).
    #[inline]
    pub(crate) fn take(&mut self, n: usize) -> io::Result<Option<&[u8]>> {
        if self.end - self.pos < n && self.fill_to(n)? < n {
            return Ok(None);
        }
        let s = self.pos;
        self.pos += n;
        Ok(Some(&self.buf[s..s + n]))
    }

    /// Skips `n` bytes; returns whether they were all there.
    pub(crate) fn skip(&mut self, mut n: u64) -> io::Result<bool> {
        while n > 0 {
            let avail = self.fill_to(1)?;
            if avail == 0 {
                return Ok(false);
            }
            let k = usize::try_from(n).unwrap_or(usize::MAX).min(avail);
            self.pos += k;
            n -= k as u64;
        }
        Ok(true)
    }

    /// Whether the input is exhausted.
    pub(crate) fn at_eof(&mut self) -> io::Result<bool> {
        Ok(self.fill_to(1)? == 0)
    }

    /// The next line without its `\n` (and a `\r` before it), or `None` at the end.
    pub(crate) fn next_line(&mut self) -> io::Result<Option<&[u8]>> {
        let mut scanned = 0;
        loop {
            let avail = &self.buf[self.pos + scanned..self.end];
            if let Some(i) = avail.iter().position(|&b| b == b'\n') {
                let start = self.pos;
                let nl = start + scanned + i;
                self.pos = nl + 1;
                return Ok(Some(strip_cr(&self.buf[start..nl])));
            }
            scanned = self.end - self.pos;
            if self.eof {
                if scanned == 0 {
                    return Ok(None);
                }
                let start = self.pos;
                self.pos = self.end;
                return Ok(Some(strip_cr(&self.buf[start..self.end])));
            }
            self.fill_to(scanned + 1)?;
        }
    }
}

fn strip_cr(line: &[u8]) -> &[u8] {
    line.strip_suffix(b"\r").unwrap_or(line)
}

/// The UTF-8 byte order mark.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// `text` without a leading UTF-8 byte order mark.
pub(crate) fn strip_bom(text: &[u8]) -> &[u8] {
    text.strip_prefix(BOM).unwrap_or(text)
}

pub(crate) fn io_error(e: &io::Error, location: Location) -> ReadError {
    ReadError::new(location, e.kind().into())
}

/// Line-oriented text reading with line numbers and whitespace tokens.
pub(crate) struct Lines<R> {
    pub(crate) input: Input<R>,
    /// The current line (comments stripped when `comment` is set).
    pub(crate) line: Vec<u8>,
    /// 1-based number of the current line (0 before the first).
    pub(crate) line_no: u64,
    comment: Option<u8>,
}

impl<R: Read> Lines<R> {
    pub(crate) fn new(input: Input<R>, comment: Option<u8>) -> Self {
        Self {
            input,
            line: Vec::new(),
            line_no: 0,
            comment,
        }
    }

    pub(crate) fn location(&self) -> Location {
        Location::Line(self.line_no)
    }

    pub(crate) fn error(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.location(), kind)
    }

    /// Reads the next line into `self.line`; false at the end of the input.
    pub(crate) fn next(&mut self) -> Result<bool, ReadError> {
        let loc = Location::Line(self.line_no + 1);
        match self.input.next_line().map_err(|e| io_error(&e, loc))? {
            None => Ok(false),
            Some(l) => {
                self.line.clear();
                // Every text format skips a byte order mark (editors on Windows add one).
                let l = if self.line_no == 0 { strip_bom(l) } else { l };
                self.line.extend_from_slice(l);
                self.line_no += 1;
                if let Some(c) = self.comment
                    && let Some(i) = self.line.iter().position(|&b| b == c)
                {
                    self.line.truncate(i);
                }
                Ok(true)
            }
        }
    }

    /// Reads the next line that holds a token; false at the end of the input.
    pub(crate) fn next_nonblank(&mut self) -> Result<bool, ReadError> {
        while self.next()? {
            if self.line.iter().any(|b| !b.is_ascii_whitespace()) {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// Whitespace-separated tokens of the current line.
    pub(crate) fn tokens(&self) -> impl Iterator<Item = &[u8]> {
        tokens(&self.line)
    }
}

pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// A token stream over lines (for formats where line breaks carry no meaning).
pub(crate) struct Tokens<R> {
    pub(crate) lines: Lines<R>,
    cursor: usize,
}

impl<R: Read> Tokens<R> {
    /// Tokens after the current line of `lines` (which is considered consumed).
    pub(crate) fn new(lines: Lines<R>) -> Self {
        let cursor = lines.line.len();
        Self { lines, cursor }
    }

    pub(crate) fn error(&self, kind: ReadErrorKind) -> ReadError {
        self.lines.error(kind)
    }

    /// Range of the next token in `self.lines.line`, reading lines as needed.
    fn advance(&mut self) -> Result<Option<(usize, usize)>, ReadError> {
        loop {
            let line = &self.lines.line;
            let mut i = self.cursor;
            while i < line.len() && line[i].is_ascii_whitespace() {
                i += 1;
            }
            if i < line.len() {
                let mut j = i;
                while j < line.len() && !line[j].is_ascii_whitespace() {
                    j += 1;
                }
                self.cursor = j;
                return Ok(Some((i, j)));
            }
            if !self.lines.next()? {
                self.cursor = self.lines.line.len();
                return Ok(None);
            }
            self.cursor = 0;
        }
    }

    /// The next token, or `None` at the end of the input.
    pub(crate) fn next(&mut self) -> Result<Option<&[u8]>, ReadError> {
        Ok(self.advance()?.map(|(i, j)| &self.lines.line[i..j]))
    }

    /// The next token, or a `Truncated` error naming what was expected.
    pub(crate) fn expect_any(&mut self, expected: &'static str) -> Result<&[u8], ReadError> {
        match self.advance()? {
            Some((i, j)) => Ok(&self.lines.line[i..j]),
            None => Err(self.error(ReadErrorKind::Truncated { expected })),
        }
    }

    /// Requires the next token to be `keyword` (ASCII case-insensitive).
    pub(crate) fn expect_keyword(&mut self, keyword: &'static str) -> Result<(), ReadError> {
        let ok = self
            .expect_any(keyword)?
            .eq_ignore_ascii_case(keyword.as_bytes());
        if ok {
            Ok(())
        } else {
            Err(self.error(ReadErrorKind::Unexpected { expected: keyword }))
        }
    }

    /// Parses the next token with `parse`, failing with `MalformedNumber`.
    pub(crate) fn number<T>(
        &mut self,
        expected: &'static str,
        parse: impl FnOnce(&[u8]) -> Option<T>,
    ) -> Result<T, ReadError> {
        let v = parse(self.expect_any(expected)?);
        v.ok_or_else(|| self.error(ReadErrorKind::MalformedNumber))
    }

    /// Drops the rest of the current line.
    pub(crate) fn skip_rest_of_line(&mut self) {
        self.cursor = self.lines.line.len();
    }
}

pub(crate) fn parse_f64(t: &[u8]) -> Option<f64> {
    std::str::from_utf8(t).ok()?.parse().ok()
}

pub(crate) fn parse_f32(t: &[u8]) -> Option<f32> {
    std::str::from_utf8(t).ok()?.parse().ok()
}

pub(crate) fn parse_i64(t: &[u8]) -> Option<i64> {
    std::str::from_utf8(t).ok()?.parse().ok()
}

pub(crate) fn parse_u64(t: &[u8]) -> Option<u64> {
    std::str::from_utf8(t).ok()?.parse().ok()
}
