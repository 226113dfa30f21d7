//! A text capture's lines, read one at a time and bounded (a line longer than [`MAX_LINE_BYTES`] is an error, not
//! an allocation), numbered for the errors.

use std::io::{BufRead, Read};

use super::CaptureError;

/// The longest line read (a TRC of 20,000 markers at 16 characters a coordinate is under 1 MiB).
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Lines of a text capture: [`Lines::next_line`] gives each without its line end.
pub struct Lines<R> {
    source: R,
    format: &'static str,
    line: u64,
    buf: Vec<u8>,
}

impl<R: BufRead> Lines<R> {
    pub fn new(source: R, format: &'static str) -> Self {
        Lines { source, format, line: 0, buf: Vec::new() }
    }

    /// The next line (without `\r\n` or `\n`) and its number (1-based), `None` at the end of the file.
    pub fn next_line(&mut self) -> Result<Option<(u64, &str)>, CaptureError> {
        self.buf.clear();
        let limit = MAX_LINE_BYTES as u64 + 1;
        let n = (&mut self.source).take(limit).read_until(b'\n', &mut self.buf).map_err(CaptureError::io("reading"))?;
        if n == 0 {
            return Ok(None);
        }
        self.line += 1;
        if self.buf.len() > MAX_LINE_BYTES {
            return Err(self.error(format!("longer than {MAX_LINE_BYTES} bytes: not a line of a {}", self.format)));
        }
        while self.buf.last().is_some_and(|b| *b == b'\n' || *b == b'\r') {
            self.buf.pop();
        }
        let format = self.format;
        let line = self.line;
        std::str::from_utf8(&self.buf).map(|text| Some((line, text))).map_err(|e| CaptureError::Text {
            format,
            line,
            reason: format!("not UTF-8 text (byte {}): not a {format}", e.valid_up_to() + 1),
        })
    }

    /// The number of the line read last (1-based).
    pub fn line(&self) -> u64 {
        self.line
    }

    /// An error at the line read last.
    pub fn error(&self, reason: String) -> CaptureError {
        CaptureError::Text { format: self.format, line: self.line, reason }
    }
}
