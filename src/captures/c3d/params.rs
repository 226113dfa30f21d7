//! The parameter section: groups (`POINT`, `ANALOG`, `TRIAL`, ...) of typed, dimensioned parameters.
//!
//! Each entry: name length (i8, negative = locked), id (i8: negative = a group, positive = a parameter of that
//! group), the name, a 16-bit offset to the next entry (0: the last), then for a parameter its type (-1 char,
//! 1 byte, 2 int16, 4 float), dimensions and data, and a description. Every length is checked against the bytes
//! left before anything is allocated, so a damaged section costs at most its own size (< 128 KiB).

use super::numbers::Processor;

/// A parameter's values.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Character data, one string per row (the first dimension is the length), trailing spaces trimmed.
    Chars(Vec<String>),
    /// Byte or 16-bit integer data.
    Ints(Vec<i16>),
    Floats(Vec<f32>),
}

/// One parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    pub group: String,
    pub name: String,
    pub dims: Vec<usize>,
    pub values: Values,
}

/// The parameters of a file, and what was odd about them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Parameters {
    pub params: Vec<Param>,
    pub warnings: Vec<String>,
}

impl Parameters {
    pub fn get(&self, group: &str, name: &str) -> Option<&Param> {
        self.params.iter().find(|p| p.group.eq_ignore_ascii_case(group) && p.name.eq_ignore_ascii_case(name))
    }

    /// The first number of an integer or float parameter.
    pub fn number(&self, group: &str, name: &str) -> Option<f64> {
        match &self.get(group, name)?.values {
            Values::Ints(v) => v.first().map(|x| f64::from(*x)),
            Values::Floats(v) => v.first().map(|x| f64::from(*x)),
            Values::Chars(_) => None,
        }
    }

    pub fn ints(&self, group: &str, name: &str) -> Option<&[i16]> {
        match &self.get(group, name)?.values {
            Values::Ints(v) => Some(v),
            _ => None,
        }
    }

    /// The rows of a character parameter.
    pub fn strings(&self, group: &str, name: &str) -> Option<&[String]> {
        match &self.get(group, name)?.values {
            Values::Chars(v) => Some(v),
            _ => None,
        }
    }

    /// `GROUP:NAME`, then `NAME2`, `NAME3`, ... (C3D splits lists longer than 255 entries so).
    pub fn string_list(&self, group: &str, name: &str) -> Vec<String> {
        let mut out: Vec<String> = self.strings(group, name).map(<[String]>::to_vec).unwrap_or_default();
        for k in 2.. {
            match self.strings(group, &format!("{name}{k}")) {
                Some(more) => out.extend_from_slice(more),
                None => break,
            }
        }
        out
    }
}

/// Parses a parameter section (`bytes` starts at its 4-byte header). Damage is a warning: the entries before it
/// are kept, and the header alone still describes the data.
pub fn parse(bytes: &[u8], processor: Processor) -> Parameters {
    let mut out = Parameters::default();
    let mut groups: Vec<(i8, String)> = Vec::new();
    let mut raw: Vec<(i8, Param)> = Vec::new();
    let mut pos = 4usize;
    loop {
        if pos >= bytes.len() {
            break; // the last entry's offset points at the section's end
        }
        let Some(&[len_byte, id_byte]) = bytes.get(pos..pos + 2) else {
            out.warnings.push("the parameter section ends without its last entry".into());
            break;
        };
        let name_len = usize::from((len_byte as i8).unsigned_abs());
        let id = id_byte as i8;
        if name_len == 0 {
            break;
        }
        let name_at = pos + 2;
        let Some(name) = bytes.get(name_at..name_at + name_len) else {
            out.warnings.push(format!("a parameter name at byte {pos} runs past the section"));
            break;
        };
        let name = String::from_utf8_lossy(name).trim().to_string();
        let offset_at = name_at + name_len;
        let Some(offset) = processor.u16_at(bytes, offset_at) else {
            out.warnings.push(format!("parameter `{name}` is cut off"));
            break;
        };
        let body = offset_at + 2;
        let next = if offset == 0 { bytes.len() } else { offset_at + usize::from(offset) };
        match id {
            0 => out.warnings.push(format!("entry `{name}` has group id 0; skipped")),
            id if id < 0 => groups.push((-id, name)),
            id => match entry(bytes, body, processor) {
                Ok((dims, values)) => raw.push((id, Param { group: String::new(), name, dims, values })),
                Err(e) => out.warnings.push(format!("parameter `{name}`: {e}; skipped")),
            },
        }
        if offset == 0 || next <= pos {
            break;
        }
        pos = next;
    }
    for (id, mut p) in raw {
        match groups.iter().find(|(g, _)| *g == id) {
            Some((_, group)) => p.group = group.clone(),
            None => {
                out.warnings.push(format!("parameter `{}` belongs to group {id}, which is not defined", p.name));
                p.group = format!("#{id}");
            }
        }
        out.params.push(p);
    }
    if out.params.is_empty() && groups.is_empty() {
        out.warnings.push("no parameter could be read: the header alone describes the data".into());
    }
    out
}

/// A parameter's dimensions and data, starting at its type byte.
fn entry(bytes: &[u8], at: usize, processor: Processor) -> Result<(Vec<usize>, Values), String> {
    let cut = || "its data runs past the section".to_string();
    let kind = *bytes.get(at).ok_or_else(cut)? as i8;
    let ndims = usize::from(*bytes.get(at + 1).ok_or_else(cut)?);
    let dims: Vec<usize> = bytes.get(at + 2..at + 2 + ndims).ok_or_else(cut)?.iter().map(|d| usize::from(*d)).collect();
    let count: usize = dims.iter().product();
    let size = match kind {
        -1 | 1 => 1,
        2 => 2,
        4 => 4,
        k => return Err(format!("unknown data type {k}")),
    };
    let data_at = at + 2 + ndims;
    // The product of at most 255 dimensions of at most 255 can be huge: checked against the bytes left first.
    let data = count.checked_mul(size).and_then(|n| bytes.get(data_at..data_at.checked_add(n)?)).ok_or_else(cut)?;
    let values = match kind {
        -1 => {
            let row = dims.first().copied().unwrap_or(1).max(1);
            Values::Chars(
                data.chunks(row)
                    .map(|c| String::from_utf8_lossy(c).trim_end_matches([' ', '\0']).to_string())
                    .collect(),
            )
        }
        1 => Values::Ints(data.iter().map(|b| i16::from(*b)).collect()),
        2 => Values::Ints(data.chunks_exact(2).map(|c| processor.i16([c[0], c[1]])).collect()),
        _ => Values::Floats(data.chunks_exact(4).map(|c| processor.f32([c[0], c[1], c[2], c[3]])).collect()),
    };
    Ok((dims, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A section: group POINT (id 1) with USED = 2 (int) and LABELS = ["A ", "BC"] (char 2x2), little-endian.
    fn section() -> Vec<u8> {
        let mut b = vec![1, 0x50, 1, 84];
        let group = |b: &mut Vec<u8>, name: &str, id: i8| {
            b.extend_from_slice(&[name.len() as u8, id as u8]);
            b.extend_from_slice(name.as_bytes());
            b.extend_from_slice(&3u16.to_le_bytes());
            b.push(0);
        };
        group(&mut b, "POINT", -1);
        let param = |b: &mut Vec<u8>, name: &str, body: &[u8], last: bool| {
            b.extend_from_slice(&[name.len() as u8, 1]);
            b.extend_from_slice(name.as_bytes());
            let offset = if last { 0u16 } else { (2 + body.len() + 1) as u16 };
            b.extend_from_slice(&offset.to_le_bytes());
            b.extend_from_slice(body);
            b.push(0);
        };
        param(&mut b, "USED", &[2, 0, 2, 0], false);
        param(&mut b, "LABELS", &[0xff, 2, 2, 2, b'A', b' ', b'B', b'C'], true);
        b
    }

    #[test]
    fn reads_groups_and_parameters() {
        let p = parse(&section(), Processor::Intel);
        assert_eq!(p.number("POINT", "USED"), Some(2.0));
        assert_eq!(p.string_list("point", "labels"), ["A", "BC"]);
        assert!(p.warnings.is_empty(), "{:?}", p.warnings);
    }

    #[test]
    fn a_cut_section_keeps_what_came_before() {
        let full = section();
        let p = parse(&full[..full.len() - 3], Processor::Intel);
        assert_eq!(p.number("POINT", "USED"), Some(2.0));
        assert!(p.get("POINT", "LABELS").is_none());
        assert_eq!(p.warnings.len(), 1);
        let none = parse(&[1, 0x50, 1, 84, 0xff], Processor::Intel);
        assert!(none.params.is_empty() && none.warnings.len() == 2, "{:?}", none.warnings);
    }
}
