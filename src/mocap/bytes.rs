//! A bounds-checked little-endian reader over one datagram: every read that would pass the end is an error,
//! never a panic, and nothing is allocated from a length field before the bytes it describes were seen.

/// The reader ran out of bytes reading `what`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("truncated: {what} at byte {at} of {len}")]
pub struct Truncated {
    pub what: &'static str,
    pub at: usize,
    pub len: usize,
}

/// A cursor over a byte slice.
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Reader { data, at: 0 }
    }

    /// Bytes read so far.
    pub fn position(&self) -> usize {
        self.at
    }

    /// Bytes left.
    pub fn remaining(&self) -> usize {
        self.data.len() - self.at
    }

    /// The next `n` bytes.
    pub fn take(&mut self, n: usize, what: &'static str) -> Result<&'a [u8], Truncated> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.data.len());
        let Some(end) = end else { return Err(Truncated { what, at: self.at, len: self.data.len() }) };
        let out = &self.data[self.at..end];
        self.at = end;
        Ok(out)
    }

    /// Skips `n` bytes.
    pub fn skip(&mut self, n: usize, what: &'static str) -> Result<(), Truncated> {
        self.take(n, what).map(|_| ())
    }

    fn array<const N: usize>(&mut self, what: &'static str) -> Result<[u8; N], Truncated> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.take(N, what)?);
        Ok(out)
    }

    pub fn u8(&mut self, what: &'static str) -> Result<u8, Truncated> {
        Ok(self.array::<1>(what)?[0])
    }
    pub fn u16(&mut self, what: &'static str) -> Result<u16, Truncated> {
        self.array(what).map(u16::from_le_bytes)
    }
    pub fn i16(&mut self, what: &'static str) -> Result<i16, Truncated> {
        self.array(what).map(i16::from_le_bytes)
    }
    pub fn u32(&mut self, what: &'static str) -> Result<u32, Truncated> {
        self.array(what).map(u32::from_le_bytes)
    }
    pub fn i32(&mut self, what: &'static str) -> Result<i32, Truncated> {
        self.array(what).map(i32::from_le_bytes)
    }
    pub fn u64(&mut self, what: &'static str) -> Result<u64, Truncated> {
        self.array(what).map(u64::from_le_bytes)
    }
    pub fn i64(&mut self, what: &'static str) -> Result<i64, Truncated> {
        self.array(what).map(i64::from_le_bytes)
    }
    pub fn f32(&mut self, what: &'static str) -> Result<f32, Truncated> {
        self.array(what).map(f32::from_le_bytes)
    }
    pub fn f64(&mut self, what: &'static str) -> Result<f64, Truncated> {
        self.array(what).map(f64::from_le_bytes)
    }
    pub fn vec3(&mut self, what: &'static str) -> Result<[f32; 3], Truncated> {
        Ok([self.f32(what)?, self.f32(what)?, self.f32(what)?])
    }

    /// A NUL-terminated string (the NUL is consumed); invalid UTF-8 is replaced. With no NUL before the end,
    /// the rest of the data is the string.
    pub fn cstr(&mut self, what: &'static str) -> Result<String, Truncated> {
        let rest = &self.data[self.at..];
        if rest.is_empty() {
            return Err(Truncated { what, at: self.at, len: self.data.len() });
        }
        let (text, used) = match rest.iter().position(|&b| b == 0) {
            Some(n) => (&rest[..n], n + 1),
            None => (rest, rest.len()),
        };
        self.at += used;
        Ok(String::from_utf8_lossy(text).into_owned())
    }

    /// A fixed-size field holding a NUL-terminated string.
    pub fn fixed_str(&mut self, n: usize, what: &'static str) -> Result<String, Truncated> {
        let field = self.take(n, what)?;
        let end = field.iter().position(|&b| b == 0).unwrap_or(field.len());
        Ok(String::from_utf8_lossy(&field[..end]).into_owned())
    }
}

/// Little-endian writing into a `Vec<u8>`, for the encoders.
pub trait Writer {
    fn put_u16(&mut self, v: u16);
    fn put_i16(&mut self, v: i16);
    fn put_u32(&mut self, v: u32);
    fn put_i32(&mut self, v: i32);
    fn put_u64(&mut self, v: u64);
    fn put_i64(&mut self, v: i64);
    fn put_f32(&mut self, v: f32);
    fn put_f64(&mut self, v: f64);
    fn put_cstr(&mut self, s: &str);
}

impl Writer for Vec<u8> {
    fn put_u16(&mut self, v: u16) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_i16(&mut self, v: i16) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_u32(&mut self, v: u32) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_i32(&mut self, v: i32) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_u64(&mut self, v: u64) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_i64(&mut self, v: i64) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_f32(&mut self, v: f32) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_f64(&mut self, v: f64) {
        self.extend_from_slice(&v.to_le_bytes());
    }
    fn put_cstr(&mut self, s: &str) {
        self.extend_from_slice(s.as_bytes());
        self.push(0);
    }
}
