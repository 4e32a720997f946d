//! Shared machinery of the text formats: a byte scanner that tracks lines and
//! parses numbers fast (`fast-float2`), and a buffered writer that prints
//! floats in their shortest round-trip form (`zmij`).

use std::io::Write;

use crate::error::{IoError, Location, Result};
use crate::format::Format;

/// Reads numbers and words from text, line by line or as a token stream.
pub(crate) struct Scanner<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    format: Format,
    comment: Option<u8>,
}

#[inline]
fn is_blank(b: u8) -> bool {
    b == b' ' || b == b'\t' || b == b'\r' || b == b'\x0c' || b == b'\x0b'
}

impl<'a> Scanner<'a> {
    /// A scanner at the start of `bytes`; `comment` starts a comment running to
    /// the end of the line.
    pub fn new(bytes: &'a [u8], format: Format, comment: Option<u8>) -> Self {
        Self { bytes, pos: 0, line: 1, format, comment }
    }

    /// The same scanner moved to byte `pos`, which is on 1-based line `line`.
    pub fn starting_at(mut self, pos: usize, line: usize) -> Self {
        self.pos = pos;
        self.line = line;
        self
    }

    /// The current line, for errors.
    pub fn at(&self) -> Location {
        Location::at_line(self.format, self.line)
    }

    /// The unread bytes.
    pub fn rest(&self) -> &'a [u8] {
        self.bytes.get(self.pos..).unwrap_or_default()
    }

    /// Byte offset of the next unread byte.
    pub fn offset(&self) -> usize {
        self.pos
    }

    #[inline]
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    #[inline]
    fn skip_blanks(&mut self) {
        while self.peek().is_some_and(is_blank) {
            self.pos += 1;
        }
    }

    /// `true` (after skipping blanks) at the end of the line: a newline, a
    /// comment or the end of the data.
    #[inline]
    pub fn at_line_end(&mut self) -> bool {
        self.skip_blanks();
        match self.peek() {
            None | Some(b'\n') => true,
            Some(b) => Some(b) == self.comment,
        }
    }

    /// `true` at the end of the data.
    pub fn is_eof(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    /// Moves to the start of the next line.
    #[inline]
    pub fn next_line(&mut self) {
        match self.rest().iter().position(|&b| b == b'\n') {
            Some(i) => {
                self.pos += i + 1;
                self.line += 1;
            }
            None => self.pos = self.bytes.len(),
        }
    }

    /// Skips blank lines, comment lines and leading whitespace up to the next
    /// content; `false` at the end of the data.
    pub fn skip_to_content(&mut self) -> bool {
        loop {
            if !self.at_line_end() {
                return true;
            }
            if self.is_eof() {
                return false;
            }
            self.next_line();
        }
    }

    /// The next whitespace-delimited word on this line, if any.
    #[inline]
    pub fn word(&mut self) -> Option<&'a [u8]> {
        if self.at_line_end() {
            return None;
        }
        let start = self.pos;
        while self.peek().is_some_and(|b| !b.is_ascii_whitespace() && Some(b) != self.comment) {
            self.pos += 1;
        }
        self.bytes.get(start..self.pos)
    }

    /// The word at the current position without consuming it, for errors.
    fn upcoming(&self) -> &'a [u8] {
        let rest = self.rest();
        let end = rest.iter().position(|b| b.is_ascii_whitespace()).unwrap_or(rest.len());
        &rest[..end]
    }

    /// A syntax error at the current word.
    pub fn error(&self, expected: impl Into<String>) -> IoError {
        IoError::syntax(self.at(), expected, self.upcoming())
    }

    /// A float on this line, `None` at the end of the line.
    ///
    /// # Errors
    /// A syntax error naming `what` when the next word is not a number.
    #[inline]
    pub fn opt_float(&mut self, what: &str) -> Result<Option<f64>> {
        if self.at_line_end() {
            return Ok(None);
        }
        match fast_float2::parse_partial::<f64, _>(self.rest()) {
            Ok((value, len)) if self.ends_word(len) => {
                self.pos += len;
                Ok(Some(value))
            }
            _ => Err(self.error(what)),
        }
    }

    /// A float on this line.
    ///
    /// # Errors
    /// A syntax error naming `what` at the end of the line or when the next
    /// word is not a number.
    #[inline]
    pub fn float(&mut self, what: &str) -> Result<f64> {
        self.opt_float(what)?.ok_or_else(|| self.error(what))
    }

    /// A (possibly signed) integer on this line, `None` at the end of the line.
    /// Stops before a `/` (OBJ face corners).
    ///
    /// # Errors
    /// A syntax error naming `what` when the next word is not an integer.
    #[inline]
    pub fn opt_int(&mut self, what: &str) -> Result<Option<i64>> {
        if self.at_line_end() {
            return Ok(None);
        }
        match parse_int(self.rest()) {
            Some((value, len)) if self.ends_word(len) || self.rest().get(len) == Some(&b'/') => {
                self.pos += len;
                Ok(Some(value))
            }
            _ => Err(self.error(what)),
        }
    }

    /// An integer on this line.
    ///
    /// # Errors
    /// A syntax error naming `what` at the end of the line or when the next
    /// word is not an integer.
    #[inline]
    pub fn int(&mut self, what: &str) -> Result<i64> {
        self.opt_int(what)?.ok_or_else(|| self.error(what))
    }

    /// Consumes `b` if it is the next byte.
    #[inline]
    pub fn eat(&mut self, b: u8) -> bool {
        let hit = self.peek() == Some(b);
        self.pos += usize::from(hit);
        hit
    }

    #[inline]
    fn ends_word(&self, len: usize) -> bool {
        match self.rest().get(len) {
            None => true,
            Some(&b) => b.is_ascii_whitespace() || Some(b) == self.comment,
        }
    }
}

/// Parses an optionally signed decimal integer at the start of `bytes`,
/// returning it and its length; `None` without digits or on overflow.
#[inline]
pub(crate) fn parse_int(bytes: &[u8]) -> Option<(i64, usize)> {
    let (negative, start) = match bytes.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let mut value: i64 = 0;
    let mut end = start;
    while let Some(d) = bytes.get(end).and_then(|b| b.checked_sub(b'0')).filter(|d| *d < 10) {
        value = value.checked_mul(10)?.checked_add(i64::from(d))?;
        end += 1;
    }
    (end > start).then_some((if negative { -value } else { value }, end))
}

/// Checks a count read from a text header: not negative, and small enough
/// that `min_bytes_each` bytes per item fit in the `available` bytes left.
pub(crate) fn check_count(
    at: &Location,
    what: &str,
    count: i64,
    min_bytes_each: u64,
    available: usize,
) -> Result<usize> {
    let refuse = |reason: String| IoError::count(at.clone(), what, count.into(), reason);
    let n = u64::try_from(count).map_err(|_| refuse("counts cannot be negative".into()))?;
    if n >= u64::from(u32::MAX) {
        return Err(refuse("more than 32-bit indices can address".into()));
    }
    if n.saturating_mul(min_bytes_each) > available as u64 + 1 {
        return Err(refuse(format!("the {available} bytes left hold at most {}", available as u64 / min_bytes_each)));
    }
    Ok(n as usize)
}

/// Resolves a face's vertex index (already 0-based) against the vertex count.
#[inline]
pub(crate) fn vertex_index(at: impl Fn() -> Location, face: usize, index: i64, count: usize) -> Result<u32> {
    if (0..count as i64).contains(&index) {
        Ok(index as u32)
    } else {
        Err(IoError::Index { at: at(), face, what: "vertex", index, count })
    }
}

/// Buffered text output: collects a chunk in memory, then hands it to the
/// underlying writer.
pub(crate) struct TextWriter<W: Write> {
    out: W,
    buf: Vec<u8>,
    floats: zmij::Buffer,
}

const CHUNK: usize = 1 << 16;

impl<W: Write> TextWriter<W> {
    /// A writer over `out`.
    pub fn new(out: W) -> Self {
        Self { out, buf: Vec::with_capacity(CHUNK + 256), floats: zmij::Buffer::new() }
    }

    /// Appends raw text.
    #[inline]
    pub fn str(&mut self, s: &str) -> &mut Self {
        self.buf.extend_from_slice(s.as_bytes());
        self
    }

    /// Appends a float in its shortest round-trip form (`1.0`, `0.1`, `1e-7`).
    #[inline]
    pub fn float(&mut self, x: f64) -> &mut Self {
        self.buf.extend_from_slice(self.floats.format(x).as_bytes());
        self
    }

    /// Appends a single-precision float in its shortest round-trip form.
    #[inline]
    pub fn float32(&mut self, x: f32) -> &mut Self {
        self.buf.extend_from_slice(self.floats.format(x).as_bytes());
        self
    }

    /// Appends `x` floats separated by spaces, each preceded by a space.
    #[inline]
    pub fn floats(&mut self, xs: &[f64]) -> &mut Self {
        for &x in xs {
            self.str(" ").float(x);
        }
        self
    }

    /// Appends an unsigned integer.
    #[inline]
    pub fn uint(&mut self, x: u64) -> &mut Self {
        let mut digits = [0u8; 20];
        let mut i = digits.len();
        let mut x = x;
        loop {
            i -= 1;
            digits[i] = b'0' + (x % 10) as u8;
            x /= 10;
            if x == 0 {
                break;
            }
        }
        self.buf.extend_from_slice(&digits[i..]);
        self
    }

    /// Appends a signed integer.
    #[inline]
    pub fn int(&mut self, x: i64) -> &mut Self {
        if x < 0 {
            self.str("-");
        }
        self.uint(x.unsigned_abs())
    }

    /// Ends a line, handing the buffer over when it is full.
    ///
    /// # Errors
    /// The writer's I/O error.
    #[inline]
    pub fn line(&mut self) -> Result<()> {
        self.buf.push(b'\n');
        if self.buf.len() >= CHUNK {
            self.out.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes out everything left.
    ///
    /// # Errors
    /// The writer's I/O error.
    pub fn finish(mut self) -> Result<()> {
        self.out.write_all(&self.buf)?;
        self.out.flush()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers() {
        assert_eq!(parse_int(b"-12/3"), Some((-12, 3)));
        assert_eq!(parse_int(b"+7"), Some((7, 2)));
        assert_eq!(parse_int(b"-"), None);
        assert_eq!(parse_int(b"99999999999999999999"), None);
    }

    #[test]
    fn scanner_tracks_lines_and_comments() {
        let mut s = Scanner::new(b"# c\n\n  1.5 2e3 # x\n7 z", Format::Off, Some(b'#'));
        assert!(s.skip_to_content());
        assert_eq!(s.at().line, Some(3));
        assert_eq!(s.float("x").unwrap(), 1.5);
        assert_eq!(s.opt_float("y").unwrap(), Some(2000.0));
        assert_eq!(s.opt_float("z").unwrap(), None);
        s.next_line();
        assert_eq!(s.int("n").unwrap(), 7);
        let e = s.float("a coordinate").unwrap_err();
        assert_eq!(e.to_string(), "OFF line 4: expected a coordinate, found `z`");
    }

    #[test]
    fn numbers_must_end_at_whitespace() {
        let mut s = Scanner::new(b"1.5x", Format::Obj, None);
        assert!(s.float("x").is_err());
    }

    #[test]
    fn writer_prints_shortest_floats() {
        let mut out = Vec::new();
        let mut w = TextWriter::new(&mut out);
        w.float(1.0).str(" ").float(0.1).str(" ").uint(0).str(" ").uint(4294967295).floats(&[-2.5]);
        w.line().unwrap();
        w.finish().unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), "1.0 0.1 0 4294967295 -2.5\n");
    }

    #[test]
    fn counts_are_checked_against_size() {
        let at = Location::new(Format::Off);
        assert_eq!(check_count(&at, "vertex", 3, 6, 20).unwrap(), 3);
        assert!(check_count(&at, "vertex", -1, 6, 20).is_err());
        assert!(check_count(&at, "vertex", 4_000_000_000, 6, 20).is_err());
        let e = check_count(&at, "vertex", 400, 6, 20).unwrap_err();
        assert!(e.to_string().contains("impossible vertex count 400"), "{e}");
    }
}
