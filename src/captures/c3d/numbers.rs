//! The three number formats of C3D files: Intel (little-endian IEEE), DEC (little-endian integers, VAX F
//! floats) and SGI/MIPS (big-endian IEEE). The parameter section's fourth byte names the format (83 + 1, 2, 3).

/// The processor type a C3D file was written for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Processor {
    Intel,
    Dec,
    Mips,
}

impl Processor {
    /// From the parameter section's fourth byte.
    pub fn from_byte(b: u8) -> Option<Self> {
        match b {
            84 => Some(Processor::Intel),
            85 => Some(Processor::Dec),
            86 => Some(Processor::Mips),
            _ => None,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Processor::Intel => "Intel",
            Processor::Dec => "DEC",
            Processor::Mips => "SGI/MIPS",
        }
    }

    #[inline]
    pub fn i16(self, b: [u8; 2]) -> i16 {
        match self {
            Processor::Mips => i16::from_be_bytes(b),
            _ => i16::from_le_bytes(b),
        }
    }

    #[inline]
    pub fn u16(self, b: [u8; 2]) -> u16 {
        match self {
            Processor::Mips => u16::from_be_bytes(b),
            _ => u16::from_le_bytes(b),
        }
    }

    /// A 32-bit float. A VAX F float is an IEEE single with its 16-bit halves swapped and an exponent bias 2
    /// higher (bias 128 and the hidden bit at 0.5), so swapping the halves and dividing by 4 gives its value.
    #[inline]
    pub fn f32(self, b: [u8; 4]) -> f32 {
        match self {
            Processor::Intel => f32::from_le_bytes(b),
            Processor::Mips => f32::from_be_bytes(b),
            Processor::Dec => f32::from_le_bytes([b[2], b[3], b[0], b[1]]) / 4.0,
        }
    }

    /// The 16-bit word at `bytes[at..at + 2]`, or `None` past the end.
    pub fn i16_at(self, bytes: &[u8], at: usize) -> Option<i16> {
        Some(self.i16(bytes.get(at..at.checked_add(2)?)?.try_into().ok()?))
    }

    pub fn u16_at(self, bytes: &[u8], at: usize) -> Option<u16> {
        Some(self.u16(bytes.get(at..at.checked_add(2)?)?.try_into().ok()?))
    }

    pub fn f32_at(self, bytes: &[u8], at: usize) -> Option<f32> {
        Some(self.f32(bytes.get(at..at.checked_add(4)?)?.try_into().ok()?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_three_formats_read_the_same_numbers() {
        assert_eq!(Processor::Intel.f32(1.5f32.to_le_bytes()), 1.5);
        assert_eq!(Processor::Mips.f32((-2.25f32).to_be_bytes()), -2.25);
        // 1.0 as a VAX F float: sign 0, exponent 129 (bias 128, fraction 0.5 x 2^1), fraction 0; stored as the
        // two little-endian 16-bit words 0x4080, 0x0000.
        assert_eq!(Processor::Dec.f32([0x80, 0x40, 0x00, 0x00]), 1.0);
        assert_eq!(Processor::Dec.f32([0, 0, 0, 0]), 0.0);
        assert_eq!(Processor::Mips.i16([0xff, 0xfe]), -2);
        assert_eq!(Processor::Dec.i16([0xfe, 0xff]), -2);
    }
}
