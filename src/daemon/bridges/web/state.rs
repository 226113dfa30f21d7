//! What the bay screens show of each rig, bounded: the last [`MAX_SHOTS`] predictions (the table, the per-club
//! numbers and the CSV), the last [`FLIGHT_LINES`] flights drawn (each the line the daemon's flight model sampled
//! while it flew the launch, from `golf/<rig>/flight`: the screen flies nothing), the shots left out, the labels, the units and
//! the last [`MAX_COMPARISONS`] comparisons with a launch monitor. Every change becomes one JSON text for the
//! pages ([`shot_json`], [`summary_json`], ...); a page that joins gets [`RigState::snapshot`].

use std::collections::{BTreeSet, VecDeque};

use serde_json::{json, Map, Value};

use crate::session::{summarize, GroupBy, ShotId, Units, METRICS};
use crate::wire::{DisplayUnits, FlightLine, LaunchPrediction, ShotLabels};

/// Predictions kept per rig (a long fitting day is a few hundred shots).
pub const MAX_SHOTS: usize = 5000;
/// Shots a page is sent when it joins (it keeps no more).
pub const PAGE_SHOTS: usize = 1000;
/// Flights kept and drawn (the last one bright, the others faded).
pub const FLIGHT_LINES: usize = 12;
/// Comparisons kept.
pub const MAX_COMPARISONS: usize = 50;
/// Flight lines kept for shots not shown yet (a line that came before its launch).
const EARLY_LINES: usize = 16;

/// One rig's screen.
#[derive(Debug, Default)]
pub struct RigState {
    pub rig: String,
    shots: Vec<LaunchPrediction>,
    /// The page message of each kept shot (same order as `shots`).
    shot_texts: Vec<String>,
    flights: VecDeque<(u64, Value)>,
    /// Lines that came before their shot's launch.
    early_lines: VecDeque<(u64, Value)>,
    excluded: BTreeSet<u64>,
    pub labels: ShotLabels,
    pub units: DisplayUnits,
    comparisons: VecDeque<Value>,
    status: Option<Value>,
    summary: Option<String>,
}

/// A number for JSON (NaN and infinities as null).
fn num(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// Every TrackMan metric of a shot, under its key in both unit systems (`ball_speed_mph`, `ball_speed_mps`).
fn metrics(p: &LaunchPrediction) -> Map<String, Value> {
    let mut m = Map::new();
    for metric in &METRICS {
        let Some(v) = (metric.value)(p) else { continue };
        for units in [Units::Imperial, Units::Metric] {
            let (_, factor) = metric.quantity.unit(units);
            m.insert(metric.quantity.key(metric.base, units), num(v * factor));
        }
    }
    // The launch's own mph figure, so the screen shows exactly what was published.
    m.insert("ball_speed_mph".into(), num(p.launch.launch.ball_speed_mph));
    m.insert("club_speed_mph".into(), num(p.delivery.club_speed_mph));
    m
}

/// The one-sigma uncertainty of every metric that has one on the shot, under the metrics' keys in both unit
/// systems (`ball_speed_mph`, `ball_speed_mps`); empty for a shot that carries none.
fn sigmas(p: &LaunchPrediction) -> Map<String, Value> {
    let mut m = Map::new();
    for metric in &METRICS {
        let Some(s) = crate::session::sigma::sigma(p, metric.base) else { continue };
        for units in [Units::Imperial, Units::Metric] {
            let (_, factor) = metric.quantity.unit(units);
            m.insert(metric.quantity.key(metric.base, units), num(s * factor));
        }
    }
    m
}

/// The flight drawn on the screen, from the daemon's line: `[x, y, z]` in metres to the centimetre, world frame
/// (x to the target, y up, z right).
pub fn screen_line(line: &FlightLine) -> Value {
    let r = |v: f64| (v * 100.0).round() / 100.0;
    Value::Array(line.points.iter().map(|q| json!([r(q[1]), r(q[2]), r(q[3])])).collect())
}

/// A shot as the pages read it.
pub fn shot_json(p: &LaunchPrediction, published_ns: u64, flight: Option<&Value>) -> Value {
    let warnings: Vec<&str> = p.launch.warnings.iter().map(|w| w.as_str()).collect();
    json!({
        "type": "shot", "rig": p.rig, "shot": p.shot, "t_impact_ns": p.t_impact_ns, "published_ns": published_ns,
        "club": crate::session::club_of(p), "club_file": p.club, "model": p.model, "labels": p.labels,
        "warnings": warnings, "quality": num(p.quality), "latency_us": num(p.latency_us),
        "impact_h_mm": num(p.delivery.impact_h_mm), "impact_v_mm": num(p.delivery.impact_v_mm),
        "m": metrics(p), "u": sigmas(p), "flight": flight,
    })
}

impl RigState {
    pub fn new(rig: &str) -> Self {
        RigState { rig: rig.to_string(), ..Default::default() }
    }

    /// Whether the shot is among the last shown (a second model's prediction of it is not a new shot).
    fn shown(&self, shot: u64) -> bool {
        self.shots.iter().rev().take(16).any(|s| s.shot == shot)
    }

    fn draw_line(&mut self, shot: u64, line: Value) {
        self.flights.push_back((shot, line));
        while self.flights.len() > FLIGHT_LINES {
            self.flights.pop_front();
        }
    }

    /// Takes a prediction (a repeated shot number, as from a second model, is ignored), with its flight's line
    /// when that came first; returns the page message.
    pub fn on_launch(&mut self, p: LaunchPrediction, published_ns: u64) -> Option<String> {
        if self.shown(p.shot) {
            return None;
        }
        let line = self.early_lines.iter().position(|(s, _)| *s == p.shot).and_then(|i| self.early_lines.remove(i));
        let line = line.map(|(_, l)| l);
        let text = shot_json(&p, published_ns, line.as_ref()).to_string();
        if let Some(line) = line {
            self.draw_line(p.shot, line);
        }
        self.shot_texts.push(shot_json(&p, published_ns, None).to_string());
        self.shots.push(p);
        if self.shots.len() > MAX_SHOTS {
            let extra = self.shots.len() - MAX_SHOTS;
            self.shots.drain(..extra);
            self.shot_texts.drain(..extra);
        }
        self.summary = None;
        Some(text)
    }

    /// Takes the line of a prediction's flight: drawn with its shot when the shot is shown (the page message
    /// returned), kept for it when it has not come yet; a shot's second line (a second model's) is ignored.
    pub fn on_flight(&mut self, line: &FlightLine) -> Option<String> {
        let drawn = self.flights.iter().chain(&self.early_lines).any(|(s, _)| *s == line.shot);
        if drawn {
            return None;
        }
        let points = screen_line(line);
        if !self.shown(line.shot) {
            self.early_lines.push_back((line.shot, points));
            while self.early_lines.len() > EARLY_LINES {
                self.early_lines.pop_front();
            }
            return None;
        }
        let text = json!({ "type": "flight", "rig": self.rig, "shot": line.shot, "line": &points }).to_string();
        self.draw_line(line.shot, points);
        Some(text)
    }

    /// A shot left out or taken back; returns the page message.
    pub fn on_exclusion(&mut self, shot: u64, excluded: bool) -> String {
        if excluded {
            self.excluded.insert(shot);
        } else {
            self.excluded.remove(&shot);
        }
        // Exclusions of shots long gone are not kept.
        if let (true, Some(first)) = (self.excluded.len() > MAX_SHOTS, self.shots.first().map(|s| s.shot)) {
            self.excluded.retain(|s| *s >= first);
        }
        self.summary = None;
        json!({ "type": "excluded", "rig": self.rig, "shots": self.excluded }).to_string()
    }

    /// The comparisons kept (JSON, newest last).
    pub fn comparisons(&self) -> impl Iterator<Item = &Value> {
        self.comparisons.iter()
    }

    pub fn on_comparison(&mut self, c: Value) -> String {
        let text = json!({ "type": "comparison", "rig": self.rig, "comparison": c }).to_string();
        self.comparisons.push_back(c);
        while self.comparisons.len() > MAX_COMPARISONS {
            self.comparisons.pop_front();
        }
        text
    }

    pub fn on_status(&mut self, s: Value) -> String {
        let text = json!({ "type": "status", "rig": self.rig, "status": s }).to_string();
        self.status = Some(s);
        text
    }

    pub fn labels_json(&self) -> String {
        json!({ "type": "labels", "rig": self.rig, "labels": self.labels }).to_string()
    }

    pub fn units_json(&self) -> String {
        json!({ "type": "units", "rig": self.rig, "units": self.units }).to_string()
    }

    /// Per club, per player and per tag (as `impactd session --by` groups): shots counted and each metric's
    /// mean and SD in both unit systems (excluded shots left out), under `by.club`, `by.player`, `by.tag`.
    pub fn summary_json(&mut self) -> String {
        if let Some(s) = &self.summary {
            return s.clone();
        }
        let excluded: BTreeSet<ShotId> =
            self.excluded.iter().map(|&shot| ShotId { rig: self.rig.clone(), shot }).collect();
        let grouped = |by: GroupBy| -> Value {
            let s = summarize(&self.shots, by, &excluded, false);
            let groups = s.groups.iter().map(|g| {
                let mut stats = Map::new();
                for units in [Units::Imperial, Units::Metric] {
                    for (i, metric) in METRICS.iter().enumerate() {
                        let (st, _) = s.stats_in(g, i, units);
                        let key = metric.quantity.key(metric.base, units);
                        stats.insert(key, json!({ "n": st.count, "mean": num(st.mean), "sd": num(st.sd) }));
                    }
                }
                json!({ "group": g.group, "shots": g.shots, "stats": stats })
            });
            Value::Array(groups.collect())
        };
        let by =
            json!({ "club": grouped(GroupBy::Club), "player": grouped(GroupBy::Player), "tag": grouped(GroupBy::Tag) });
        let text = json!({ "type": "summary", "rig": self.rig, "by": by }).to_string();
        self.summary = Some(text.clone());
        text
    }

    /// Everything a page needs when it joins, as one JSON text.
    pub fn snapshot(&mut self) -> String {
        let from = self.shot_texts.len().saturating_sub(PAGE_SHOTS);
        let shots = format!("[{}]", self.shot_texts[from..].join(","));
        let flights: Vec<Value> =
            self.flights.iter().map(|(shot, line)| json!({ "shot": shot, "line": line })).collect();
        let head = json!({
            "type": "snapshot", "rig": self.rig, "excluded": self.excluded, "labels": self.labels,
            "units": self.units, "flights": flights, "comparisons": self.comparisons, "status": self.status,
        })
        .to_string();
        let summary = self.summary_json();
        // `head` ends with `}`: the shots and the summary join it without parsing them again.
        format!("{},\"shots\":{shots},\"summary\":{summary}}}", &head[..head.len() - 1])
    }

    /// The kept predictions, in order.
    pub fn shots(&self) -> &[LaunchPrediction] {
        &self.shots
    }

    pub fn excluded(&self) -> &BTreeSet<u64> {
        &self.excluded
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prediction(shot: u64) -> LaunchPrediction {
        let line = include_str!("../../../../tests/data/web-launch.json");
        let mut p: LaunchPrediction = serde_json::from_str(line).unwrap();
        p.shot = shot;
        p
    }

    #[test]
    fn a_rig_keeps_at_most_its_bounds_however_long_it_runs() {
        let mut s = RigState::new("rig1");
        for shot in 0..(MAX_SHOTS as u64 + 300) {
            assert!(s.on_launch(prediction(shot), 1).is_some());
            assert!(s.on_flight(&line(shot, 1.0)).is_some());
            s.on_comparison(json!({ "shot": shot }));
        }
        assert_eq!(s.shots().len(), MAX_SHOTS);
        assert_eq!(s.shots()[0].shot, 300);
        assert_eq!(s.flights.len(), FLIGHT_LINES);
        assert_eq!(s.comparisons.len(), MAX_COMPARISONS);
        let snap: Value = serde_json::from_str(&s.snapshot()).unwrap();
        assert_eq!(snap["shots"].as_array().unwrap().len(), PAGE_SHOTS);
        assert_eq!(snap["summary"]["by"]["club"][0]["shots"], json!(MAX_SHOTS));
        // A second model's prediction of the same shot is not a new shot.
        assert!(s.on_launch(prediction(MAX_SHOTS as u64 + 299), 1).is_none());
    }

    #[test]
    fn an_excluded_shot_leaves_the_averages() {
        let mut s = RigState::new("rig1");
        let mut slow = prediction(2);
        slow.launch.launch.ball_speed_mps *= 0.5;
        for p in [prediction(1), slow, prediction(3)] {
            s.on_launch(p, 1);
        }
        let mean = |s: &mut RigState| {
            let v: Value = serde_json::from_str(&s.summary_json()).unwrap();
            (
                v["by"]["club"][0]["shots"].as_u64().unwrap(),
                v["by"]["club"][0]["stats"]["ball_speed_mps"]["mean"].as_f64().unwrap(),
            )
        };
        let full = prediction(1).launch.launch.ball_speed_mps;
        let (n, m) = mean(&mut s);
        assert_eq!(n, 3);
        assert!((m - full * (2.5 / 3.0)).abs() < 1e-9, "{m}");
        s.on_exclusion(2, true);
        let (n, m) = mean(&mut s);
        assert_eq!(n, 2);
        assert!((m - full).abs() < 1e-9, "{m}");
    }

    #[test]
    fn the_screen_draws_the_daemons_line_whichever_comes_first() {
        let mut s = RigState::new("rig1");
        // The usual order: the launch, then its line.
        let shot: Value = serde_json::from_str(&s.on_launch(prediction(1), 1).unwrap()).unwrap();
        assert_eq!(shot["flight"], Value::Null);
        let drawn: Value = serde_json::from_str(&s.on_flight(&line(1, 1.0)).unwrap()).unwrap();
        assert_eq!((drawn["type"].as_str(), drawn["shot"].as_u64()), (Some("flight"), Some(1)));
        // Its points are the line's, to the centimetre.
        assert_eq!(drawn["line"], json!([[0.0, 0.0, 0.0], [10.0, 2.0, -0.12], [20.0, 0.0, -0.25]]));
        // A second model's line of the same shot is not drawn again.
        assert!(s.on_flight(&line(1, 2.0)).is_none());
        // A line that comes before its launch goes out with it.
        assert!(s.on_flight(&line(2, 1.0)).is_none());
        let shot: Value = serde_json::from_str(&s.on_launch(prediction(2), 1).unwrap()).unwrap();
        assert_eq!(shot["flight"][1], json!([10.0, 2.0, -0.12]));
        let snap: Value = serde_json::from_str(&s.snapshot()).unwrap();
        let shots: Vec<u64> = snap["flights"].as_array().unwrap().iter().map(|f| f["shot"].as_u64().unwrap()).collect();
        assert_eq!(shots, [1, 2]);
    }

    fn line(shot: u64, scale: f64) -> FlightLine {
        FlightLine {
            rig: "rig1".into(),
            shot,
            model: "adjusted".into(),
            t_impact_ns: 0,
            step_s: 0.05,
            points: vec![[0.0; 4], [0.5, 10.0 * scale, 2.001, -0.123], [1.0, 20.0 * scale, 0.0, -0.249]],
        }
    }
}
