//! QTM real-time packets as QTM (the server) or a client writes them: the commands the bridge sends, and the
//! server side the test servers and benchmarks use. Qualisys' Python SDK (`qtm-rt`) checks them in the tests.

use super::{
    Body6d, Frame6d, COMPONENT_3D, COMPONENT_6D, COMPONENT_6D_RES, HEADER_BYTES, PACKET_COMMAND, PACKET_DATA,
    PACKET_ERROR, PACKET_EVENT, PACKET_NO_MORE_DATA, PACKET_XML,
};
use crate::mocap::bytes::Writer;

fn packet(kind: u32, body: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_BYTES + body.len());
    out.put_u32((HEADER_BYTES + body.len()) as u32);
    out.put_u32(kind);
    out.extend_from_slice(body);
    out
}

fn string(kind: u32, text: &str) -> Vec<u8> {
    let mut body = Vec::with_capacity(text.len() + 1);
    body.put_cstr(text);
    packet(kind, &body)
}

/// A command (client) or a command reply (server).
pub fn command(text: &str) -> Vec<u8> {
    string(PACKET_COMMAND, text)
}

pub fn error(text: &str) -> Vec<u8> {
    string(PACKET_ERROR, text)
}

pub fn xml(text: &str) -> Vec<u8> {
    string(PACKET_XML, text)
}

pub fn event(code: u8) -> Vec<u8> {
    packet(PACKET_EVENT, &[code])
}

pub fn no_more_data() -> Vec<u8> {
    packet(PACKET_NO_MORE_DATA, &[])
}

/// A data packet holding one 6D (or, when every body has a residual, 6DRes) component, and a 3D component when
/// the frame has markers.
pub fn data(frame: &Frame6d) -> Vec<u8> {
    let residual = !frame.bodies.is_empty() && frame.bodies.iter().all(|b| b.residual_mm.is_some());
    let per_body = if residual { 52 } else { 48 };
    let mut c = Vec::with_capacity(16 + frame.bodies.len() * per_body);
    c.put_u32((HEADER_BYTES + 8 + frame.bodies.len() * per_body) as u32);
    c.put_u32(if residual { COMPONENT_6D_RES } else { COMPONENT_6D });
    c.put_u32(frame.bodies.len() as u32);
    c.put_u16(frame.drop_rate_2d);
    c.put_u16(frame.out_of_sync_rate_2d);
    for Body6d { position_mm, rotation, residual_mm } in &frame.bodies {
        position_mm.iter().chain(rotation.iter()).for_each(|&v| c.put_f32(v));
        if residual {
            c.put_f32(residual_mm.unwrap_or(0.0));
        }
    }
    let markers = !frame.markers_mm.is_empty();
    if markers {
        c.put_u32((HEADER_BYTES + 8 + frame.markers_mm.len() * 12) as u32);
        c.put_u32(COMPONENT_3D);
        c.put_u32(frame.markers_mm.len() as u32);
        c.put_u16(frame.drop_rate_2d);
        c.put_u16(frame.out_of_sync_rate_2d);
        frame.markers_mm.iter().flatten().for_each(|&v| c.put_f32(v));
    }
    let mut body = Vec::with_capacity(16 + c.len());
    body.put_i64(frame.timestamp_us);
    body.put_u32(frame.frame_number);
    body.put_u32(if markers { 2 } else { 1 });
    body.extend_from_slice(&c);
    packet(PACKET_DATA, &body)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").replace('\'', "&apos;")
}

/// The XML of a `GetParameters 3D` reply naming the marker `labels` in index order, as QTM 2023 sends it.
pub fn parameters_3d(labels: &[&str]) -> String {
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<QTM_Parameters_Ver_1.25>\n");
    x += &the_3d(labels);
    x += "</QTM_Parameters_Ver_1.25>\n";
    x
}

/// The `<The_3D>` section naming `labels`.
pub fn the_3d(labels: &[&str]) -> String {
    let mut x = String::from(
        "  <The_3D>\n    <AxisUpwards>+Z</AxisUpwards>\n    <CalibrationTime>2026-11-25 09:00:00</CalibrationTime>\n",
    );
    x += &format!("    <Labels>{}</Labels>\n", labels.len());
    for name in labels {
        x += &format!(
            "    <Label>\n      <Name>{}</Name>\n      <RGBColor>16711680</RGBColor>\n    </Label>\n",
            escape(name)
        );
    }
    x += "    <Bones/>\n  </The_3D>\n";
    x
}

/// The XML of a `GetParameters 6D` reply naming `bodies` in index order, laid out as QTM 2023 sends it.
pub fn parameters_6d(bodies: &[&str]) -> String {
    let mut x = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<QTM_Parameters_Ver_1.25>\n  <The_6D>\n");
    x += &format!("    <Bodies>{}</Bodies>\n", bodies.len());
    for name in bodies {
        x += "    <Body>\n";
        x += &format!("      <Name>{}</Name>\n", escape(name));
        x += "      <Enabled>true</Enabled>\n      <Color R=\"255\" G=\"0\" B=\"0\"/>\n";
        x += "      <MaximumResidual>10</MaximumResidual>\n      <MinimumMarkersInBody>3</MinimumMarkersInBody>\n";
        x += "      <BoneLengthTolerance>5</BoneLengthTolerance>\n      <Filter Preset=\"No filter\"/>\n";
        x += "      <Points>\n";
        for (i, p) in [[0.0, 0.0, 0.0], [40.0, 0.0, 0.0], [0.0, 30.0, 0.0]].iter().enumerate() {
            x += &format!(
                "        <Point X=\"{}\" Y=\"{}\" Z=\"{}\" Virtual=\"0\" PhysicalId=\"0\" Name=\"{}_{}\"/>\n",
                p[0],
                p[1],
                p[2],
                escape(name),
                i + 1
            );
        }
        x += "      </Points>\n      <Data_origin>0</Data_origin>\n    </Body>\n";
    }
    x += "    <Euler>\n      <First>X</First>\n      <Second>Y</Second>\n      <Third>Z</Third>\n    </Euler>\n";
    x += "  </The_6D>\n</QTM_Parameters_Ver_1.25>\n";
    x
}
