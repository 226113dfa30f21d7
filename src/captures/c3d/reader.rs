//! Opening a C3D file: the header block, the parameter section, and the data section frame by frame.

use std::io::{Read, Seek, SeekFrom};

use super::numbers::Processor;
use super::params::{self, Parameters};
use super::{C3dError, C3dInfo, Frame};
use crate::math::Vector3;

const BLOCK: u64 = 512;
/// The parameter section read at most (the format's own count is a byte: 255 blocks).
const MAX_PARAM_BLOCKS: u64 = 1024;

/// A C3D file being read: what it holds, then its frames one at a time (memory: one frame).
pub struct C3dReader<R> {
    pub info: C3dInfo,
    source: R,
    raw: Vec<u8>,
    next_index: u64,
}

impl<R: Read + Seek> C3dReader<R> {
    /// Reads the header and the parameters, and positions the reader on the first frame.
    pub fn new(mut source: R) -> Result<Self, C3dError> {
        let file_bytes = source.seek(SeekFrom::End(0)).map_err(C3dError::io("measuring"))?;
        source.seek(SeekFrom::Start(0)).map_err(C3dError::io("seeking to the header"))?;
        let mut header = [0u8; BLOCK as usize];
        let short = file_bytes < BLOCK;
        let have = usize::try_from(file_bytes.min(BLOCK)).unwrap_or(0);
        read_exact(&mut source, &mut header[..have], "the header block")?;
        if short || header[1] != 0x50 {
            // An empty file (BTK's `Empty.c3d`) or a cut header: say so rather than judge a byte that is not there.
            if header[1] == 0x50 || file_bytes < 2 {
                return Err(C3dError::NotC3d(format!("it has {file_bytes} bytes, less than a 512-byte header")));
            }
            return Err(C3dError::NotC3d(format!("its second byte is 0x{:02x}; a C3D header's is 0x50", header[1])));
        }
        let param_block = u64::from(header[0].max(1));
        source.seek(SeekFrom::Start((param_block - 1) * BLOCK)).map_err(C3dError::io("seeking to the parameters"))?;
        let mut first = [0u8; 4];
        read_exact(&mut source, &mut first, "the parameter section")?;
        let processor = Processor::from_byte(first[3]).ok_or_else(|| {
            C3dError::Parameters(format!(
                "processor type byte {} is none of 84 (Intel), 85 (DEC), 86 (SGI/MIPS)",
                first[3]
            ))
        })?;
        // Some writers count the parameter blocks short: the section runs to the data when the data follow it.
        let data_block = u64::from(processor.u16_at(&header, 16).unwrap_or(0));
        let param_blocks = u64::from(first[2]).max(data_block.saturating_sub(param_block)).clamp(1, MAX_PARAM_BLOCKS);
        let mut section = vec![0u8; (param_blocks * BLOCK) as usize];
        section[..4].copy_from_slice(&first);
        let available = file_bytes.saturating_sub((param_block - 1) * BLOCK + 4);
        let want = (section.len() - 4).min(usize::try_from(available).unwrap_or(usize::MAX));
        read_exact(&mut source, &mut section[4..4 + want], "the parameter section")?;
        section.truncate(4 + want);
        let parameters = params::parse(&section, processor);
        let info = layout(&header, processor, parameters, file_bytes)?;
        source.seek(SeekFrom::Start(info.data_start_byte)).map_err(C3dError::io("seeking to the data"))?;
        let raw = vec![0u8; info.frame_bytes];
        Ok(C3dReader { info, source, raw, next_index: 0 })
    }

    /// Reads the next frame into `frame` (its vectors are reused); `false` after the last.
    pub fn next_frame(&mut self, frame: &mut Frame) -> Result<bool, C3dError> {
        if self.next_index >= self.info.frames {
            return Ok(false);
        }
        let index = self.next_index;
        read_exact(&mut self.source, &mut self.raw, "a frame").map_err(|e| match e {
            C3dError::Io { source, .. } => C3dError::Frame { index, source },
            other => other,
        })?;
        self.next_index += 1;
        decode(&self.info, &self.raw, index, frame);
        Ok(true)
    }
}

fn read_exact(source: &mut impl Read, buf: &mut [u8], what: &'static str) -> Result<(), C3dError> {
    source.read_exact(buf).map_err(C3dError::io(what))
}

/// Where the data are and how to read them, from the header (the layout writers keep) and the parameters.
fn layout(header: &[u8], p: Processor, parameters: Parameters, file_bytes: u64) -> Result<C3dInfo, C3dError> {
    let word = |n: usize| p.u16_at(header, 2 * (n - 1)).unwrap_or(0);
    let mut warnings = parameters.warnings.clone();
    let points = usize::from(word(2));
    let analog_words = usize::from(word(3));
    let scale = p.f32_at(header, 12).unwrap_or(0.0);
    let float_data = scale < 0.0;
    if scale == 0.0 || !scale.is_finite() {
        warnings.push(format!("the header's scale is {scale}: integer coordinates would all read 0"));
    }
    let mut data_block = u64::from(word(9));
    if data_block == 0 {
        data_block = parameters.number("POINT", "DATA_START").map(|v| v as u16 as u64).unwrap_or(0);
    }
    if data_block < 2 {
        return Err(C3dError::Layout(format!("the data start block is {data_block}")));
    }
    // The rate as its shortest decimal (25 Hz, not the f32's 25.0000019).
    let mut rate_hz = shortest(p.f32_at(header, 20).unwrap_or(0.0));
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        rate_hz = parameters.number("POINT", "RATE").unwrap_or(0.0);
    }
    if !(rate_hz.is_finite() && rate_hz > 0.0 && rate_hz < 1e6) {
        return Err(C3dError::Layout(format!("the frame rate {rate_hz} Hz is not a rate")));
    }
    if let Some(used) = parameters.number("POINT", "USED") {
        if used as u16 as usize != points {
            warnings.push(format!("POINT:USED is {used} but the header has {points} points; the header is used"));
        }
    }
    let mut first_frame = u64::from(word(4));
    let mut last_frame = u64::from(word(5));
    // Long captures overflow the header's 16-bit frame numbers: TRIAL:ACTUAL_START/END_FIELD hold 32 bits.
    let field = |name: &str| {
        parameters
            .ints("TRIAL", name)
            .filter(|v| v.len() >= 2)
            .map(|v| u64::from(v[0] as u16) | u64::from(v[1] as u16) << 16)
    };
    if let (Some(s), Some(e)) = (field("ACTUAL_START_FIELD"), field("ACTUAL_END_FIELD")) {
        (first_frame, last_frame) = (s, e);
    }
    let mut frames = (last_frame + 1).saturating_sub(first_frame);
    // And POINT:LONG_FRAMES (a float) the frame count past 65535.
    if let Some(n) = parameters.number("POINT", "LONG_FRAMES").filter(|n| n.is_finite() && *n > 0.0 && *n < 1e12) {
        frames = frames.max(n as u64);
    } else if let Some(n) = parameters.number("POINT", "FRAMES") {
        let n = n as i64 as u16 as u64;
        if n > frames && frames == u64::from(u16::MAX) {
            frames = n;
        }
    }
    let word_bytes = if float_data { 4 } else { 2 };
    let frame_bytes = (4 * points + analog_words) * word_bytes;
    let data_start_byte = (data_block - 1) * BLOCK;
    let stored = if frame_bytes == 0 { 0 } else { file_bytes.saturating_sub(data_start_byte) / frame_bytes as u64 };
    if stored < frames {
        warnings.push(format!("truncated: {stored} of the {frames} frames the header announces are in the file"));
        frames = stored;
    }
    let units = parameters.strings("POINT", "UNITS").and_then(|u| u.first().cloned()).unwrap_or_default();
    let metres_per_unit = match units.trim().to_ascii_lowercase().as_str() {
        "mm" => 1e-3,
        "cm" => 1e-2,
        // Some writers cut "meters" to the parameter's 4 characters.
        "m" | "mete" | "meter" | "meters" | "metre" | "metres" => 1.0,
        "in" | "inch" | "inches" => 0.0254,
        _ if points == 0 => 1e-3,
        other => {
            warnings.push(format!("POINT:UNITS `{other}` is not mm, cm, m or in: millimetres assumed"));
            1e-3
        }
    };
    let mut labels = parameters.string_list("POINT", "LABELS");
    if labels.len() < points {
        warnings.push(format!("{} labels for {points} points: the others are named P<n>", labels.len()));
        labels.extend((labels.len()..points).map(|i| format!("P{}", i + 1)));
    }
    labels.truncate(points);
    let mut analog_labels = parameters.string_list("ANALOG", "LABELS");
    if let Some(used) = parameters.number("ANALOG", "USED").map(|u| u as u16 as usize) {
        analog_labels.resize_with(used, String::new);
        for (i, l) in analog_labels.iter_mut().enumerate().filter(|(_, l)| l.is_empty()) {
            *l = format!("A{}", i + 1);
        }
    }
    let analog_rate_hz = parameters.number("ANALOG", "RATE").map(|r| shortest(r as f32)).unwrap_or(0.0);
    Ok(C3dInfo {
        processor: p,
        rate_hz,
        first_frame,
        frames,
        labels,
        units,
        metres_per_unit,
        scale,
        float_data,
        analog_words,
        analog_labels,
        analog_rate_hz,
        data_start_byte,
        frame_bytes,
        warnings,
        parameters,
    })
}

fn shortest(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(f64::from(v))
}

/// One frame's points: lab-frame positions in metres and validity from each point's residual word.
fn decode(info: &C3dInfo, raw: &[u8], index: u64, frame: &mut Frame) {
    let p = info.processor;
    let n = info.labels.len();
    frame.index = index;
    frame.points_m.clear();
    frame.residual_m.clear();
    let scale = f64::from(info.scale.abs());
    let to_m = info.metres_per_unit;
    for i in 0..n {
        let (xyz, word) = if info.float_data {
            let at = 16 * i;
            let f = |k: usize| f64::from(p.f32([raw[at + k], raw[at + k + 1], raw[at + k + 2], raw[at + k + 3]]));
            let w = f(12);
            // The fourth float holds the 16-bit residual word's value (camera mask << 8 | residual).
            let word = if (-32768.0..=65535.0).contains(&w) { w as i32 } else { -1 };
            ([f(0), f(4), f(8)], if word > 32767 { word - 65536 } else { word })
        } else {
            let at = 8 * i;
            let w = |k: usize| f64::from(p.i16([raw[at + k], raw[at + k + 1]]));
            ([w(0) * scale, w(2) * scale, w(4) * scale], i32::from(p.i16([raw[at + 6], raw[at + 7]])))
        };
        let valid = word >= 0 && xyz.iter().all(|v| v.is_finite());
        frame.points_m.push(valid.then(|| Vector3::new(xyz[0], xyz[1], xyz[2]) * to_m));
        frame.residual_m.push(if valid { (word & 0xff) as f32 * info.scale.abs() * to_m as f32 } else { -1.0 });
    }
}
