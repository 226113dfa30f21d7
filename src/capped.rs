//! Reading small input files (club, soil and configuration files) with a size cap, so a path such as
//! `/dev/zero` or a huge file is refused instead of read until memory runs out.

use std::io::Read;
use std::path::Path;

/// The largest club, soil or configuration file read (bytes).
pub const MAX_INPUT_FILE_BYTES: u64 = 1 << 20;

/// The file's text, refused with `InvalidData` when it holds more than `max_bytes` bytes.
pub fn read_to_string(path: &Path, max_bytes: u64) -> std::io::Result<String> {
    let mut text = String::new();
    std::fs::File::open(path)?.take(max_bytes + 1).read_to_string(&mut text)?;
    if text.len() as u64 > max_bytes {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("larger than the {max_bytes}-byte limit of an input file"),
        ));
    }
    Ok(text)
}

/// The most of one field or message an error quotes (characters).
pub const QUOTE_CHARS: usize = 120;

/// `text` as an error may quote it: whole when short, else its first [`QUOTE_CHARS`] characters and how long
/// it was, so an error never echoes a huge field whole.
pub fn quote(text: &str) -> std::borrow::Cow<'_, str> {
    match text.char_indices().nth(QUOTE_CHARS) {
        None => std::borrow::Cow::Borrowed(text),
        Some((end, _)) => std::borrow::Cow::Owned(format!("{}... ({} bytes)", &text[..end], text.len())),
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_long_text_is_quoted_short() {
        assert_eq!(super::quote("short"), "short");
        let long = "é".repeat(100_000);
        let q = super::quote(&long);
        assert!(q.chars().count() < 150 && q.ends_with("(200000 bytes)"), "{q}");
    }

    #[test]
    fn dev_zero_is_refused() {
        if std::path::Path::new("/dev/zero").exists() {
            let e = super::read_to_string("/dev/zero".as_ref(), 1024).unwrap_err();
            assert!(e.to_string().contains("1024-byte limit") || e.kind() == std::io::ErrorKind::InvalidData);
        }
    }
}
