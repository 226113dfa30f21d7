//! NatNet messages as a server (Motive) or a client writes them: the requests the bridge sends, and the server
//! side the test servers and benchmarks use. The layouts are those `natnet.rs` reads; OptiTrack's Python
//! client (`natnetsdk`) checks them in the tests.

use super::{Frame, ServerInfo, Version, NAT_CONNECT, NAT_FRAMEOFDATA, NAT_MODELDEF, NAT_SERVERINFO, RIGID_BODY_BYTES};
use crate::mocap::bytes::Writer;

/// Header + payload; `None` when the payload is over the `u16` count NatNet can describe.
fn packet(id: u16, payload: &[u8]) -> Option<Vec<u8>> {
    let n = u16::try_from(payload.len()).ok()?;
    let mut out = Vec::with_capacity(4 + payload.len());
    out.put_u16(id);
    out.put_u16(n);
    out.extend_from_slice(payload);
    Some(out)
}

/// A request without a payload (`NAT_REQUEST_MODELDEF`, `NAT_KEEPALIVE`, ...).
pub fn request(id: u16) -> Vec<u8> {
    let mut out = Vec::with_capacity(4);
    out.put_u16(id);
    out.put_u16(0);
    out
}

/// `NAT_CONNECT` as the NatNet SDK sends it: the client's name in a 256-byte field, two unused version words,
/// "subscribed data only" and the bitstream version wanted (`[0, 0]`: the server's own), NUL-terminated.
pub fn connect(client_name: &str, wanted: Option<Version>) -> Vec<u8> {
    let mut payload = vec![0u8; 271];
    let name = client_name.as_bytes();
    let n = name.len().min(255);
    payload[..n].copy_from_slice(&name[..n]);
    if let Some(v) = wanted {
        payload[265] = v.major;
        payload[266] = v.minor;
    }
    packet(NAT_CONNECT, &payload).unwrap_or_default()
}

/// The version a `NAT_CONNECT` payload asks for (`None`: the server's own).
pub fn connect_wants(payload: &[u8]) -> Option<Version> {
    let (major, minor) = (*payload.get(265)?, *payload.get(266)?);
    (major != 0).then_some(Version { major, minor })
}

/// `NAT_SERVERINFO` (`sSender_Server`).
pub fn server_info(info: &ServerInfo) -> Vec<u8> {
    let mut p = vec![0u8; 256];
    let name = info.app_name.as_bytes();
    let n = name.len().min(255);
    p[..n].copy_from_slice(&name[..n]);
    p.extend_from_slice(&info.app_version);
    p.extend_from_slice(&info.natnet_version);
    p.put_u64(info.clock_hz.unwrap_or(0));
    p.put_u16(info.data_port.unwrap_or(0));
    p.push(u8::from(info.multicast.unwrap_or(false)));
    p.extend_from_slice(&info.multicast_group.unwrap_or([0; 4]));
    packet(NAT_SERVERINFO, &p).unwrap_or_default()
}

/// `NAT_MODELDEF` as a capture volume with a force plate describes itself: one marker set (named after the
/// first body, three markers), the first rigid body, a force plate, a device and a camera, then the other rigid
/// bodies `(id, name)`, each with no markers of its own. A reader of NatNet 3.x or 4.0 (no byte sizes) must walk
/// the plate, the device and the camera to reach the bodies after them.
pub fn model_def(version: Version, bodies: &[(i32, &str)]) -> Option<Vec<u8>> {
    model_def_with_sets(version, bodies, &[])
}

/// A marker set that is an asset of its own (a club with markers and no rigid body): its id, name and markers'
/// names, in the order its labelled markers are numbered.
#[derive(Debug, Clone, Copy)]
pub struct MarkerAsset<'a> {
    pub id: i32,
    pub name: &'a str,
    pub markers: &'a [&'a str],
}

/// [`model_def`] with `assets` after the bodies: each as Motive describes it, a marker set (type 0) and, in
/// NatNet 4.1 and later, a Trained Markerset asset (type 6) with its id and markers; before 4.1 (no asset
/// descriptions) a rigid body of that name and id carries the id.
pub fn model_def_with_sets(version: Version, bodies: &[(i32, &str)], assets: &[MarkerAsset]) -> Option<Vec<u8>> {
    let mut p = Vec::new();
    let others = if bodies.is_empty() { 0 } else { 3 };
    p.put_i32(bodies.len() as i32 + 1 + others + 2 * assets.len() as i32);
    let set_name = bodies.first().map_or("all", |b| b.1);
    dataset(&mut p, version, 0, |d| {
        d.put_cstr(set_name);
        d.put_i32(3);
        for m in ["m1", "m2", "m3"] {
            d.put_cstr(m);
        }
    });
    for (i, &(id, name)) in bodies.iter().enumerate() {
        dataset(&mut p, version, 1, |d| {
            d.put_cstr(name);
            d.put_i32(id);
            d.put_i32(-1);
            for _ in 0..3 {
                d.put_f32(0.0);
            }
            d.put_i32(0);
        });
        if i == 0 {
            dataset(&mut p, version, 3, force_plate);
            dataset(&mut p, version, 4, device);
            dataset(&mut p, version, 5, camera);
        }
    }
    for a in assets {
        dataset(&mut p, version, 0, |d| {
            d.put_cstr(a.name);
            d.put_i32(a.markers.len() as i32);
            a.markers.iter().for_each(|m| d.put_cstr(m));
        });
        if version.sized_sections() {
            dataset(&mut p, version, 6, |d| asset(d, a));
        } else {
            dataset(&mut p, version, 1, |d| {
                d.put_cstr(a.name);
                d.put_i32(a.id);
                d.put_i32(-1);
                (0..3).for_each(|_| d.put_f32(0.0));
                d.put_i32(0);
            });
        }
    }
    packet(NAT_MODELDEF, &p)
}

/// An asset description (type 6): name, type (1), id, no rigid bodies, its markers (name, id, position, size,
/// params).
fn asset(d: &mut Vec<u8>, a: &MarkerAsset) {
    d.put_cstr(a.name);
    d.put_i32(1);
    d.put_i32(a.id);
    d.put_i32(0);
    d.put_i32(a.markers.len() as i32);
    for (i, m) in a.markers.iter().enumerate() {
        d.put_cstr(m);
        d.put_i32(i as i32 + 1);
        (0..3).for_each(|_| d.put_f32(0.0));
        d.put_f32(0.014);
        d.put_i16(0);
    }
}

/// A force plate description: id 1, serial `FP-0001`, 0.6 x 0.4 m, an identity calibration matrix, six channels.
fn force_plate(d: &mut Vec<u8>) {
    d.put_i32(1);
    d.put_cstr("FP-0001");
    d.put_f32(0.6);
    d.put_f32(0.4);
    for v in [0.0, 0.0, -0.04] {
        d.put_f32(v);
    }
    for row in 0..12 {
        for col in 0..12 {
            d.put_f32(if row == col { 1.0 } else { 0.0 });
        }
    }
    for corner in [[0.3, 0.2, 0.0], [-0.3, 0.2, 0.0], [-0.3, -0.2, 0.0], [0.3, -0.2, 0.0]] {
        for v in corner {
            d.put_f32(v);
        }
    }
    d.put_i32(2);
    d.put_i32(0);
    let channels = ["Fx", "Fy", "Fz", "Mx", "My", "Mz"];
    d.put_i32(channels.len() as i32);
    for c in channels {
        d.put_cstr(c);
    }
}

/// A device description (an analog board): id 2, two channels.
fn device(d: &mut Vec<u8>) {
    d.put_i32(2);
    d.put_cstr("NI-DAQ");
    d.put_cstr("DAQ-0002");
    d.put_i32(1);
    d.put_i32(0);
    d.put_i32(2);
    d.put_cstr("trigger");
    d.put_cstr("sync");
}

/// A camera description: name, position, orientation (x y z w).
fn camera(d: &mut Vec<u8>) {
    d.put_cstr("Prime 41 #1");
    for v in [2.0, 2.5, 3.0, 0.0, 0.0, 0.0, 1.0] {
        d.put_f32(v);
    }
}

fn dataset(p: &mut Vec<u8>, version: Version, kind: i32, body: impl FnOnce(&mut Vec<u8>)) {
    p.put_i32(kind);
    let mut d = Vec::new();
    body(&mut d);
    if version.sized_sections() {
        p.put_i32(d.len() as i32);
    }
    p.extend_from_slice(&d);
}

/// Writes a section: its count, (4.1+) its byte size, and its items.
fn section(p: &mut Vec<u8>, version: Version, count: usize, items: impl FnOnce(&mut Vec<u8>)) {
    p.put_i32(count as i32);
    let mut d = Vec::new();
    items(&mut d);
    if version.sized_sections() {
        p.put_i32(d.len() as i32);
    }
    p.extend_from_slice(&d);
}

/// `NAT_FRAMEOFDATA` as Motive lays it out for `version`, with `markers` in one marker set (named `set_name`)
/// and the frame's labeled markers (when it has none: `markers` as labeled markers of the first rigid body, as a
/// tracked rigid body's markers appear). `None` when the frame is over the 64 KiB a NatNet datagram can hold.
pub fn frame(version: Version, f: &Frame, set_name: &str, markers: &[[f32; 3]]) -> Option<Vec<u8>> {
    let mut p = Vec::with_capacity(64 + f.rigid_bodies.len() * RIGID_BODY_BYTES + markers.len() * 40);
    p.put_i32(f.frame_number);
    section(&mut p, version, 1, |d| {
        d.put_cstr(set_name);
        d.put_i32(markers.len() as i32);
        for m in markers {
            m.iter().for_each(|&v| d.put_f32(v));
        }
    });
    section(&mut p, version, 0, |_| {});
    section(&mut p, version, f.rigid_bodies.len(), |d| {
        for b in &f.rigid_bodies {
            d.put_i32(b.id);
            b.position_m.iter().for_each(|&v| d.put_f32(v));
            b.orientation_xyzw.iter().for_each(|&v| d.put_f32(v));
            d.put_f32(b.mean_error_m);
            d.put_i16(i16::from(b.tracking_valid));
        }
    });
    section(&mut p, version, 0, |_| {});
    if version.sized_sections() {
        section(&mut p, version, 0, |_| {});
    }
    let labeled = &f.labeled_markers;
    section(&mut p, version, if labeled.is_empty() { markers.len() } else { labeled.len() }, |d| {
        for m in labeled {
            d.put_i32(m.id);
            m.position_m.iter().for_each(|&v| d.put_f32(v));
            d.put_f32(m.size_m);
            d.put_i16(m.params);
            d.put_f32(m.residual_m);
        }
        for (i, m) in markers.iter().enumerate().filter(|_| labeled.is_empty()) {
            d.put_i32(((f.rigid_bodies.first().map_or(0, |b| b.id)) << 16) | (i as i32 + 1));
            m.iter().for_each(|&v| d.put_f32(v));
            d.put_f32(0.014);
            d.put_i16(0);
            d.put_f32(0.0002);
        }
    });
    section(&mut p, version, 0, |_| {});
    section(&mut p, version, 0, |_| {});
    p.put_u32(0);
    p.put_u32(0);
    p.put_f64(f.timestamp_s);
    p.put_u64(f.mid_exposure_ticks);
    p.put_u64(f.data_received_ticks);
    p.put_u64(f.transmit_ticks);
    if version.major >= 4 {
        p.put_u32(f.timestamp_s as u32);
        p.put_u32(((f.timestamp_s.fract()) * 4_294_967_296.0) as u32);
    }
    p.put_i16(if f.models_changed { 2 } else { 0 });
    packet(NAT_FRAMEOFDATA, &p)
}
