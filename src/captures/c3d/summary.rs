//! What `impactd info` says about a C3D capture, as text and as JSON.

use serde::Serialize;

use super::C3dInfo;

/// The JSON of `impactd info CAPTURE.c3d --json`.
#[derive(Debug, Clone, Serialize)]
pub struct C3dSummary {
    pub rate_hz: f64,
    pub frames: u64,
    pub first_frame: u64,
    pub last_frame: u64,
    pub duration_s: f64,
    pub markers: Vec<String>,
    pub units: String,
    pub processor: &'static str,
    /// `integer` or `float`.
    pub data: &'static str,
    pub analog_channels: Vec<String>,
    pub analog_rate_hz: f64,
    pub warnings: Vec<String>,
}

impl C3dSummary {
    pub fn new(info: &C3dInfo) -> Self {
        C3dSummary {
            rate_hz: info.rate_hz,
            frames: info.frames,
            first_frame: info.first_frame,
            last_frame: info.last_frame(),
            duration_s: info.frames as f64 / info.rate_hz,
            markers: info.labels.clone(),
            units: info.units.clone(),
            processor: info.processor.name(),
            data: if info.float_data { "float" } else { "integer" },
            analog_channels: info.analog_labels.clone(),
            analog_rate_hz: info.analog_rate_hz,
            warnings: info.warnings.clone(),
        }
    }

    pub fn text(&self) -> String {
        let mut out = format!(
            "C3D capture: {} frames at {} Hz ({:.3} s), frames {}..{}\n",
            self.frames, self.rate_hz, self.duration_s, self.first_frame, self.last_frame
        );
        out.push_str(&format!("data:       {} ({})\n", self.data, self.processor));
        out.push_str(&format!("units:      {}\n", if self.units.is_empty() { "(none)" } else { &self.units }));
        out.push_str(&format!("markers:    {}: {}\n", self.markers.len(), self.markers.join(", ")));
        out.push_str(&format!(
            "analog:     {} channels at {} Hz{}{}\n",
            self.analog_channels.len(),
            self.analog_rate_hz,
            if self.analog_channels.is_empty() { "" } else { ": " },
            self.analog_channels.join(", ")
        ));
        for w in &self.warnings {
            out.push_str(&format!("warning:    {w}\n"));
        }
        out
    }
}
