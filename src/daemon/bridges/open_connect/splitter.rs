//! Splits a TCP byte stream into JSON objects that have no delimiter between them (Open Connect v1 sends and
//! answers `{...}{...}`, glued together or split across reads at any byte).
//!
//! A byte-level scanner tracks the nesting depth outside strings (and escapes inside them), so an object ends at
//! the brace that closes its first one, whatever the reads. Bytes between objects other than whitespace are
//! garbage: counted and reported (before the next object, or at the end of the read), then skipped. An object longer than the cap is not kept: its
//! bytes are counted until it closes, then it is reported as oversized, so one bad message never costs the
//! next one and memory stays bounded.

/// What the stream held.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Frame {
    /// One complete object's bytes, `{` to `}`.
    Object(Vec<u8>),
    /// An object longer than the cap, discarded (its length in bytes).
    Oversized { bytes: usize },
    /// Bytes outside any object that were not whitespace.
    Garbage { bytes: usize },
}

/// The scanner's state between reads.
#[derive(Debug)]
pub struct Splitter {
    max_bytes: usize,
    buf: Vec<u8>,
    depth: usize,
    in_string: bool,
    escape: bool,
    /// Bytes of the current object when it went over the cap.
    oversized: Option<usize>,
    garbage: usize,
}

impl Splitter {
    /// A splitter that keeps objects of at most `max_bytes`.
    pub fn new(max_bytes: usize) -> Self {
        Splitter { max_bytes, buf: Vec::new(), depth: 0, in_string: false, escape: false, oversized: None, garbage: 0 }
    }

    /// Bytes held of an object not yet closed.
    pub fn pending(&self) -> usize {
        self.oversized.unwrap_or(self.buf.len())
    }

    /// Scans one read, calling `out` for every frame it completes.
    pub fn push(&mut self, data: &[u8], out: &mut impl FnMut(Frame)) {
        for &b in data {
            if self.depth == 0 {
                if b == b'{' {
                    if self.garbage > 0 {
                        out(Frame::Garbage { bytes: std::mem::take(&mut self.garbage) });
                    }
                    self.depth = 1;
                    self.in_string = false;
                    self.escape = false;
                    self.oversized = None;
                    self.buf.clear();
                    self.buf.push(b);
                } else if !b.is_ascii_whitespace() {
                    self.garbage += 1;
                }
                continue;
            }
            match &mut self.oversized {
                Some(n) => *n += 1,
                None if self.buf.len() >= self.max_bytes => {
                    self.oversized = Some(self.buf.len() + 1);
                    self.buf = Vec::new();
                }
                None => self.buf.push(b),
            }
            if self.in_string {
                if self.escape {
                    self.escape = false;
                } else if b == b'\\' {
                    self.escape = true;
                } else if b == b'"' {
                    self.in_string = false;
                }
                continue;
            }
            match b {
                b'"' => self.in_string = true,
                b'{' | b'[' => self.depth += 1,
                b'}' | b']' => {
                    self.depth -= 1;
                    if self.depth == 0 {
                        match self.oversized.take() {
                            Some(bytes) => out(Frame::Oversized { bytes }),
                            None => out(Frame::Object(std::mem::take(&mut self.buf))),
                        }
                    }
                }
                _ => {}
            }
        }
        if self.garbage > 0 {
            out(Frame::Garbage { bytes: std::mem::take(&mut self.garbage) });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn split(reads: &[&[u8]], max: usize) -> Vec<Frame> {
        let mut s = Splitter::new(max);
        let mut frames = Vec::new();
        for r in reads {
            s.push(r, &mut |f| frames.push(f));
        }
        frames
    }

    fn obj(s: &str) -> Frame {
        Frame::Object(s.as_bytes().to_vec())
    }

    #[test]
    fn glued_objects_come_out_one_by_one() {
        let f = split(&[br#"{"Code":200}{"Code":201,"Player":{"Handed":"RH"}} {"a":[1,{"b":2}]}"#], 1024);
        assert_eq!(
            f,
            vec![obj(r#"{"Code":200}"#), obj(r#"{"Code":201,"Player":{"Handed":"RH"}}"#), obj(r#"{"a":[1,{"b":2}]}"#)]
        );
    }

    #[test]
    fn an_object_split_at_every_byte_is_whole() {
        let text = r#"{"Message":"a } and a { and \" in a string","Code":200}"#;
        let reads: Vec<&[u8]> = text.as_bytes().chunks(1).collect();
        assert_eq!(split(&reads, 1024), vec![obj(text)]);
    }

    #[test]
    fn garbage_is_reported_and_skipped() {
        let f = split(&[b"hello {\"a\":1}\r\n", b"]]{\"b\":2}"], 1024);
        assert_eq!(
            f,
            vec![Frame::Garbage { bytes: 5 }, obj(r#"{"a":1}"#), Frame::Garbage { bytes: 2 }, obj(r#"{"b":2}"#)]
        );
        assert_eq!(split(&[b"{\"a\":1} junk"], 1024), vec![obj(r#"{"a":1}"#), Frame::Garbage { bytes: 4 }]);
    }

    #[test]
    fn an_oversized_object_is_dropped_and_the_next_one_kept() {
        let big = format!(r#"{{"pad":"{}"}}"#, "x".repeat(100));
        let f = split(&[big.as_bytes(), br#"{"Code":200}"#], 64);
        assert_eq!(f, vec![Frame::Oversized { bytes: big.len() }, obj(r#"{"Code":200}"#)]);
        // The cap counts the whole object: exactly at the cap is kept.
        let exact = r#"{"a":"xx"}"#;
        assert_eq!(split(&[exact.as_bytes()], exact.len()), vec![obj(exact)]);
        assert_eq!(split(&[exact.as_bytes()], exact.len() - 1), vec![Frame::Oversized { bytes: exact.len() }]);
    }
}
