//! A writer that hands each complete line written through it to a [`LineSink`], which rewrites it (a JSON line
//! given its flight, a JSON line turned into a table row) onto its own output: the line splitting every such
//! adaptor needs, once. A last line without its newline is handed over at `flush`.

use std::io::Write;

/// What a [`LineWriter`] hands each line to.
pub trait LineSink {
    /// One line, without its newline.
    fn line(&mut self, line: &[u8]) -> std::io::Result<()>;
    /// Flushes the sink's own output.
    fn flush_out(&mut self) -> std::io::Result<()>;
}

/// Splits what is written into lines for its sink.
pub struct LineWriter<S: LineSink> {
    sink: S,
    pending: Vec<u8>,
}

impl<S: LineSink> LineWriter<S> {
    pub fn new(sink: S) -> Self {
        LineWriter { sink, pending: Vec::new() }
    }
}

impl<S: LineSink> Write for LineWriter<S> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.pending.extend_from_slice(buf);
        while let Some(end) = self.pending.iter().position(|&b| b == b'\n') {
            let line: Vec<u8> = self.pending.drain(..=end).collect();
            self.sink.line(&line[..end])?;
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        if !self.pending.is_empty() {
            let line = std::mem::take(&mut self.pending);
            self.sink.line(&line)?;
        }
        self.sink.flush_out()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Upper(Vec<u8>);

    impl LineSink for Upper {
        fn line(&mut self, line: &[u8]) -> std::io::Result<()> {
            self.0.extend(line.to_ascii_uppercase());
            self.0.push(b'|');
            Ok(())
        }
        fn flush_out(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// Lines split across writes are whole when handed over; the last one without a newline comes at flush.
    #[test]
    fn lines_arrive_whole_and_the_last_at_flush() -> std::io::Result<()> {
        let mut w = LineWriter::new(Upper(Vec::new()));
        w.write_all(b"ab")?;
        w.write_all(b"c\nde\nf")?;
        assert_eq!(w.sink.0, b"ABC|DE|");
        w.flush()?;
        assert_eq!(w.sink.0, b"ABC|DE|F|");
        Ok(())
    }
}
