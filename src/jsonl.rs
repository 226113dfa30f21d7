//! Line-oriented JSON processing shared by the `predict`, `flight` and `replay` commands: one object in, one
//! object out, and a bad line answered with `{"line": N, "error": "..."}` without stopping the others.

use std::io::{BufRead, Write};

use serde::de::DeserializeOwned;
use serde::Serialize;

/// The answer to a bad line.
#[derive(Serialize)]
struct LineError<'a> {
    line: usize,
    error: &'a str,
}

/// What happened over a whole input.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Tally {
    pub answered: usize,
    pub rejected: usize,
}

/// Errors of a whole run (a bad line is not one of them).
#[derive(Debug, thiserror::Error)]
pub enum JsonlError {
    #[error("reading input: {0}")]
    Read(#[source] std::io::Error),
    #[error("reading input line {line}: {source}")]
    Line {
        line: usize,
        #[source]
        source: std::io::Error,
    },
    #[error("writing output: {0}")]
    Write(#[source] std::io::Error),
}

/// Why a line is not a valid message; the message names the field where serde can.
#[derive(Debug, thiserror::Error)]
pub enum ParseError {
    #[error("not valid JSON: {0}")]
    Syntax(serde_json::Error),
    #[error("{0}")]
    Data(serde_json::Error),
}

/// The longest line read from a JSONL input (bytes, without its newline): a longer one (`/dev/zero`, a file
/// that is not JSONL) ends the read with an error instead of being held whole.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Reads the next line into `buf` (without its `\n`), holding at most `max_bytes`: `Ok(false)` at the end of
/// the input, an `InvalidData` error for a longer line.
pub fn read_line(input: &mut impl BufRead, buf: &mut Vec<u8>, max_bytes: usize) -> std::io::Result<bool> {
    buf.clear();
    let mut any = false;
    loop {
        let chunk = match input.fill_buf() {
            Ok(c) => c,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if chunk.is_empty() {
            return Ok(any);
        }
        any = true;
        let (part, end) = match chunk.iter().position(|b| *b == b'\n') {
            Some(i) => (&chunk[..i], Some(i + 1)),
            None => (chunk, None),
        };
        if buf.len() + part.len() > max_bytes {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("a line longer than the {max_bytes}-byte limit (not JSONL)"),
            ));
        }
        buf.extend_from_slice(part);
        let used = end.unwrap_or(part.len());
        input.consume(used);
        if end.is_some() {
            return Ok(true);
        }
    }
}

/// Parses one line as a `T`.
pub fn parse_line<T: DeserializeOwned>(line: &str) -> Result<T, ParseError> {
    serde_json::from_str(line).map_err(|e| match e.classify() {
        serde_json::error::Category::Syntax | serde_json::error::Category::Eof => ParseError::Syntax(e),
        _ => ParseError::Data(e),
    })
}

/// Copies the fields of an input line that its reader does not use (`known` are the ones it does) into the
/// answer, after the answer's own: labels and earlier tools' fields travel down a pipe
/// (`predict | flight | plot trajectory`). A field the answer already has keeps the answer's value.
pub fn pass_through(
    input: serde_json::Map<String, serde_json::Value>,
    answer: &mut serde_json::Map<String, serde_json::Value>,
    known: &[&str],
) {
    for (key, value) in input {
        if !known.contains(&key.as_str()) && !answer.contains_key(&key) {
            answer.insert(key, value);
        }
    }
}

/// Runs `answer` over every non-blank line of `input`, writing one JSON line per input line to `out` and one
/// message per bad line to `err` (`<tool>: line N: <reason>`).
pub fn process<I, O, E, F>(
    tool: &str,
    input: impl BufRead,
    out: impl Write,
    err: impl Write,
    mut answer: F,
) -> Result<Tally, JsonlError>
where
    I: DeserializeOwned,
    O: Serialize,
    E: std::fmt::Display,
    F: FnMut(I) -> Result<O, E>,
{
    process_many(tool, input, out, err, |i| answer(i).map(|o| vec![o]))
}

/// As [`process`], with each good line answered by as many lines as `answer` gives.
pub fn process_many<I, O, E, F>(
    tool: &str,
    input: impl BufRead,
    mut out: impl Write,
    mut err: impl Write,
    mut answer: F,
) -> Result<Tally, JsonlError>
where
    I: DeserializeOwned,
    O: Serialize,
    E: std::fmt::Display,
    F: FnMut(I) -> Result<Vec<O>, E>,
{
    let mut tally = Tally::default();
    let mut input = input;
    let mut buf = Vec::new();
    for n in 1.. {
        if !read_line(&mut input, &mut buf, MAX_LINE_BYTES).map_err(|e| JsonlError::Line { line: n, source: e })? {
            break;
        }
        // A line that is not UTF-8 is answered like any other bad line.
        let result = match std::str::from_utf8(&buf) {
            Ok(line) if line.trim().is_empty() => continue,
            Ok(line) => match parse_line::<I>(line) {
                Ok(i) => answer(i).map_err(|e| e.to_string()),
                Err(e) => Err(e.to_string()),
            },
            Err(e) => Err(format!("not UTF-8 text: {e}")),
        };
        match result {
            Ok(answers) => {
                tally.answered += 1;
                for o in answers {
                    let text = serde_json::to_string(&o).map_err(|e| JsonlError::Write(std::io::Error::other(e)))?;
                    writeln!(out, "{text}").map_err(JsonlError::Write)?;
                }
            }
            Err(reason) => {
                tally.rejected += 1;
                writeln!(err, "{tool}: line {n}: {reason}").map_err(JsonlError::Write)?;
                let text = serde_json::to_string(&LineError { line: n, error: &reason })
                    .map_err(|e| JsonlError::Write(std::io::Error::other(e)))?;
                writeln!(out, "{text}").map_err(JsonlError::Write)?;
            }
        }
    }
    out.flush().map_err(JsonlError::Write)?;
    Ok(tally)
}
