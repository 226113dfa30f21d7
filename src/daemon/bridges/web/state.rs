//! What the bay screens show of each rig, bounded: the last [`MAX_SHOTS`] predictions (the table, the per-club
//! numbers and the CSV), the last [`FLIGHT_LINES`] flights drawn, the shots left out, the labels, the units and
//! the last [`MAX_COMPARISONS`] comparisons with a launch monitor. Every change becomes one JSON text for the
//! pages ([`shot_json`], [`summary_json`], ...); a page that joins gets [`RigState::snapshot`].

use std::collections::{BTreeSet, VecDeque};

use serde_json::{json, Map, Value};

use crate::session::{summarize, GroupBy, ShotId, Units, METRICS};
use crate::wire::{DisplayUnits, LaunchPrediction, ShotLabels};

/// Predictions kept per rig (a long fitting day is a few hundred shots).
pub const MAX_SHOTS: usize = 5000;
/// Shots a page is sent when it joins (it keeps no more).
pub const PAGE_SHOTS: usize = 1000;
/// Flights kept and drawn (the last one bright, the others faded).
pub const FLIGHT_LINES: usize = 12;
/// Comparisons kept.
pub const MAX_COMPARISONS: usize = 50;
/// The flight line's time step (s).
const FLIGHT_STEP_S: f64 = 0.1;

/// One rig's screen.
#[derive(Debug, Default)]
pub struct RigState {
    pub rig: String,
    /// The rig's flight model (its `[rig.conditions]`): the lines drawn land where its predictions say.
    flight: crate::flight::Flight,
    shots: Vec<LaunchPrediction>,
    /// The page message of each kept shot (same order as `shots`).
    shot_texts: Vec<String>,
    flights: VecDeque<(u64, Value)>,
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

/// The flight drawn on the screen, flown by `flight`: `[x, y, z]` in metres, world frame (x to the target, y up,
/// z right).
pub fn flight_line(p: &LaunchPrediction, flight: &crate::flight::Flight) -> Value {
    let launch = crate::flight::LaunchState {
        velocity_mps: p.launch.ball_velocity_mps.into(),
        spin_radps: p.launch.ball_spin_radps.into(),
    };
    let t = flight.fly(&launch, FLIGHT_STEP_S);
    let r = |v: f64| (v * 100.0).round() / 100.0;
    Value::Array(t.points.iter().map(|q| json!([r(q[1]), r(q[2]), r(q[3])])).collect())
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
    pub fn new(rig: &str, flight: crate::flight::Flight) -> Self {
        RigState { rig: rig.to_string(), flight, ..Default::default() }
    }

    /// Takes a prediction (a repeated shot number, as from a second model, is ignored); returns the page message.
    pub fn on_launch(&mut self, p: LaunchPrediction, published_ns: u64) -> Option<String> {
        if self.shots.iter().rev().take(16).any(|s| s.shot == p.shot) {
            return None;
        }
        let line = flight_line(&p, &self.flight);
        let text = shot_json(&p, published_ns, Some(&line)).to_string();
        self.flights.push_back((p.shot, line));
        while self.flights.len() > FLIGHT_LINES {
            self.flights.pop_front();
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
        let mut s = RigState::new("rig1", Default::default());
        for shot in 0..(MAX_SHOTS as u64 + 300) {
            assert!(s.on_launch(prediction(shot), 1).is_some());
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
        let mut s = RigState::new("rig1", Default::default());
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
    fn the_flight_line_lands_where_the_rigs_flight_model_says() {
        use crate::flight::{Conditions, Flight, LaunchState};
        let p = prediction(1);
        let launch = LaunchState {
            velocity_mps: p.launch.ball_velocity_mps.into(),
            spin_radps: p.launch.ball_spin_radps.into(),
        };
        // Denver's altitude: thinner air, a longer carry.
        let thin = Flight { conditions: Conditions { altitude_m: 1600.0, ..Default::default() }, ..Default::default() };
        let landing_x = |line: &Value| -> f64 {
            let pts = line.as_array().unwrap();
            let y = |q: &Value| q[1].as_f64().unwrap();
            let apex = (0..pts.len()).max_by(|&a, &b| y(&pts[a]).total_cmp(&y(&pts[b]))).unwrap();
            pts[apex..].iter().find(|q| y(q) <= 0.05).unwrap()[0].as_f64().unwrap()
        };
        let mut carries = Vec::new();
        for flight in [Flight::default(), thin] {
            let carry_m = flight.fly(&launch, FLIGHT_STEP_S).carry_m;
            let mut s = RigState::new("rig1", flight);
            let shot: Value = serde_json::from_str(&s.on_launch(p.clone(), 1).unwrap()).unwrap();
            // The first sample within 5 cm of the ground is at most one step (0.1 s, under 4 m at landing speed)
            // from the landing.
            let x = landing_x(&shot["flight"]);
            assert!((x - carry_m).abs() <= 4.0, "line lands at {x} m, the model's carry {carry_m} m");
            carries.push((carry_m, x));
        }
        // The lines are told apart: 1600 m up carries several metres further (thinner air).
        assert!(carries[1].0 > carries[0].0 * 1.03, "altitude should carry further: {carries:?}");
        assert!(carries[1].1 > carries[0].1 + 4.0, "{carries:?}");
    }
}
