//! NatNet's labelled markers: one entry of a frame's labeled-marker list, as Motive streams it in NatNet 3.x and
//! 4.x (OptiTrack's `NatNetTypes.h` `sMarker`, and its Python client `natnetsdk`, which unpacks the same fields):
//!
//! | bytes | field |
//! |---|---|
//! | 4 | id: the asset's (model's) id in the high 16 bits, the marker's 1-based index in the asset in the low 16 |
//! | 12 | position (m, f32 x y z, lab frame) |
//! | 4 | size (marker diameter, m) |
//! | 2 | params: bit 0 occluded, 1 point-cloud solved, 2 model solved, 3 has a model, 4 unlabelled, 5 active |
//! | 4 | residual (m; NatNet 3.0 and later) |
//!
//! From NatNet 4.1 the section's byte size says how long each entry is, so a later minor that appends fields
//! still decodes (the caller takes each entry's stride from it).

use crate::mocap::bytes::{Reader, Truncated};

/// Bytes of one labelled marker in NatNet 3.x and 4.x.
pub const LABELED_MARKER_BYTES: usize = 4 + 12 + 4 + 2 + 4;

/// params bit 0: the marker is not seen in this frame (its position is the last one, or a prediction).
pub const OCCLUDED: i16 = 0x01;
/// params bit 1: the position comes from the cameras' point cloud.
pub const POINT_CLOUD_SOLVED: i16 = 0x02;
/// params bit 2: the position was filled in by the asset's model solver.
pub const MODEL_SOLVED: i16 = 0x04;

/// One labelled marker of a frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LabeledMarker {
    /// The packed id (model id << 16 | marker index).
    pub id: i32,
    pub position_m: [f32; 3],
    pub size_m: f32,
    pub params: i16,
    pub residual_m: f32,
}

impl LabeledMarker {
    /// The asset (model) id: the high 16 bits of the id, as the SDK's `NatNet_DecodeID` splits it.
    pub fn model_id(&self) -> i32 {
        (self.id >> 16) & 0xffff
    }

    /// The marker's index within its asset (1-based): the low 16 bits.
    pub fn member_id(&self) -> i32 {
        self.id & 0xffff
    }

    /// The packed id of marker `member` of asset `model`.
    pub fn pack_id(model: i32, member: i32) -> i32 {
        ((model & 0xffff) << 16) | (member & 0xffff)
    }

    /// A measured position: not occluded, not a position only the model solver filled in, and finite.
    pub fn measured(&self) -> bool {
        let model_only = self.params & MODEL_SOLVED != 0 && self.params & POINT_CLOUD_SOLVED == 0;
        self.params & OCCLUDED == 0 && !model_only && self.position_m.iter().all(|v| v.is_finite())
    }
}

/// Reads one labelled marker (NatNet 3.x and 4.x; the residual is there from 3.0 on).
pub fn labeled_marker(r: &mut Reader) -> Result<LabeledMarker, Truncated> {
    Ok(LabeledMarker {
        id: r.i32("labeled marker id")?,
        position_m: r.vec3("labeled marker position")?,
        size_m: r.f32("labeled marker size")?,
        params: r.i16("labeled marker params")?,
        residual_m: r.f32("labeled marker residual")?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_split_as_the_sdk_splits_them() {
        let m = LabeledMarker { id: LabeledMarker::pack_id(5, 3), ..Default::default() };
        assert_eq!((m.id, m.model_id(), m.member_id()), (0x0005_0003, 5, 3));
        let seen = LabeledMarker { params: POINT_CLOUD_SOLVED, ..m };
        assert!(seen.measured());
        assert!(!LabeledMarker { params: OCCLUDED | POINT_CLOUD_SOLVED, ..m }.measured());
        assert!(!LabeledMarker { params: MODEL_SOLVED, ..m }.measured());
        assert!(LabeledMarker { params: MODEL_SOLVED | POINT_CLOUD_SOLVED, ..m }.measured());
        assert!(!LabeledMarker { position_m: [f32::NAN, 0.0, 0.0], ..seen }.measured());
    }
}
