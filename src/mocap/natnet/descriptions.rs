//! The NatNet data descriptions the bridge does not use but must walk past: force plates (type 3), devices (4),
//! cameras (5) and assets (6). In NatNet 3.x and 4.0 a data set carries no byte size, so a model definition that
//! lists a force plate before the club's rigid body can only be read to the club by walking the plate's fields.
//! The layouts are those of OptiTrack's NatNet SDK (its Python client `natnetsdk`, `NatNetClient.py`, unpacks
//! them field by field; the tests check the test server's bytes with it).

use crate::mocap::bytes::{Reader, Truncated};

/// Why a description could not be walked.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DescriptionError {
    #[error(transparent)]
    Truncated(#[from] Truncated),
    #[error("{what} count {count} is negative")]
    NegativeCount { what: &'static str, count: i32 },
}

fn count(r: &mut Reader, what: &'static str) -> Result<usize, DescriptionError> {
    let n = r.i32(what)?;
    usize::try_from(n).map_err(|_| DescriptionError::NegativeCount { what, count: n })
}

/// `count` NUL-terminated channel names.
fn channel_names(r: &mut Reader) -> Result<(), DescriptionError> {
    for _ in 0..count(r, "channels")? {
        r.cstr("channel name")?;
    }
    Ok(())
}

/// Type 3: id, serial number, width and length (f32), origin (3 f32), a 12x12 calibration matrix (f32), four
/// corners (12 f32), plate type, channel data type, and the channels' names.
pub fn skip_force_plate(r: &mut Reader) -> Result<(), DescriptionError> {
    r.skip(4, "force plate id")?;
    r.cstr("force plate serial number")?;
    r.skip(4 + 4 + 12 + 12 * 12 * 4 + 12 * 4 + 4 + 4, "force plate geometry")?;
    channel_names(r)
}

/// Type 4: id, name, serial number, device type, channel data type, and the channels' names.
pub fn skip_device(r: &mut Reader) -> Result<(), DescriptionError> {
    r.skip(4, "device id")?;
    r.cstr("device name")?;
    r.cstr("device serial number")?;
    r.skip(4 + 4, "device type")?;
    channel_names(r)
}

/// Type 5: name, position (3 f32), orientation (4 f32).
pub fn skip_camera(r: &mut Reader) -> Result<(), DescriptionError> {
    r.cstr("camera name")?;
    Ok(r.skip(12 + 16, "camera pose")?)
}

/// Type 6 (NatNet 4.1+, always sized there): name, asset type, id, its rigid bodies (each as a type-1
/// description, through `rigid_body`) and its markers (name, id, position, size, params). Gives the asset's id
/// and name: a Trained Markerset's labelled markers carry that id as their model id.
pub fn asset<E: From<DescriptionError> + From<Truncated>>(
    r: &mut Reader,
    mut rigid_body: impl FnMut(&mut Reader) -> Result<(), E>,
) -> Result<(i32, String), E> {
    let name = r.cstr("asset name")?;
    r.skip(4, "asset type")?;
    let id = r.i32("asset id")?;
    for _ in 0..count(r, "asset rigid bodies")? {
        rigid_body(r)?;
    }
    for _ in 0..count(r, "asset markers")? {
        r.cstr("asset marker name")?;
        r.skip(4 + 12 + 4 + 2, "asset marker")?;
    }
    Ok((id, name))
}

/// Type 0: a marker set's name and its markers' names, in the order its labelled markers are numbered.
pub fn marker_set(r: &mut Reader) -> Result<(String, Vec<String>), DescriptionError> {
    let name = r.cstr("marker set name")?;
    let mut markers = Vec::new();
    for _ in 0..count(r, "marker set markers")? {
        markers.push(r.cstr("marker name")?);
    }
    Ok((name, markers))
}
