//! `impactd predict` as a library: JSONL deliveries in, JSONL launch conditions out, each bad line answered with
//! an error that names the field (ARCHITECTURE.md section 4) without stopping the others.

use std::io::{BufRead, Write};

use serde::Serialize;
use serde_json::{Map, Value};

use crate::equipment::ClubSpec;
use crate::impact::report::WireReports;
use crate::impact::{DeliveryMetrics, Equipment, Fields, ImpactError, ImpactModel, ImpactState, RunOptions, Trace};
use crate::jsonl::{JsonlError, Tally};
use crate::wire::{DeliveryInput, PredictOutput};

/// How each delivery is answered.
#[derive(Clone, Copy)]
pub enum Predictor<'a> {
    /// The launch of a model.
    Plain(&'a dyn ImpactModel),
    /// A model resolved in time: its launch with the contact's course (`predict --trace`).
    Traced(&'a dyn ImpactModel),
}

/// An answer: the launch, the model's report (the ground model's `ground` object) and, with `--trace`, the
/// contact's course (its summary numbers beside the launch, then the trace).
#[derive(Serialize)]
struct Answer {
    #[serde(flatten)]
    output: PredictOutput,
    #[serde(flatten)]
    reports: WireReports,
    #[serde(flatten, skip_serializing_if = "Fields::is_empty")]
    course_summary: Fields,
    #[serde(skip_serializing_if = "Option::is_none")]
    trace: Option<Trace>,
}

/// A prediction error for the delivery it came from, naming the field it is about.
#[derive(Debug, thiserror::Error)]
pub enum DeliveryError {
    #[error("field `club_speed_mph`: {speed_mph:.1} mph ({speed_mps:.1} m/s) is outside 1-100 m/s")]
    Speed { speed_mph: f64, speed_mps: f64 },
    #[error("fields `impact_h_mm`/`impact_v_mm`: {0}")]
    Location(ImpactError),
    #[error("field `{field}`: must be a finite number")]
    NotFinite { field: &'static str },
    #[error("fields `club_path_deg`/`face_angle_deg`/`dynamic_loft_deg`: {0}")]
    Direction(ImpactError),
    #[error("{0}")]
    Model(ImpactError),
    #[error("{0}")]
    Implausible(#[from] crate::wire::OutOfBounds),
    /// The line is JSON but not a delivery (a field of the wrong type), or an answer that is not JSON.
    #[error("{0}")]
    Input(#[source] serde_json::Error),
    /// An answer that is not a JSON object.
    #[error("an answer that is not an object")]
    NotAnObject,
}

impl DeliveryError {
    /// Names the field `err` is about in `input`.
    pub fn new(err: ImpactError, input: &DeliveryInput) -> Self {
        match err {
            ImpactError::SpeedOutOfRange { speed_mps } => {
                DeliveryError::Speed { speed_mph: input.club_speed_mph, speed_mps }
            }
            ImpactError::OffFace { .. } | ImpactError::Face(_) => DeliveryError::Location(err),
            ImpactError::NotFinite { field } => DeliveryError::NotFinite { field },
            ImpactError::NotApproaching => DeliveryError::Direction(err),
            other => DeliveryError::Model(other),
        }
    }
}

/// The club's state at impact for a delivery read from JSON, or the reason it has none.
pub fn state_of(input: &DeliveryInput, club: &ClubSpec, equipment: &Equipment) -> Result<ImpactState, DeliveryError> {
    input.check_finite().map_err(|e| DeliveryError::new(e, input))?;
    input.check_plausible()?;
    let lie_rad = input.dynamic_lie_deg.map(f64::to_radians);
    input.to_delivery(club.loft_deg()).to_state_with_lie(equipment, lie_rad).map_err(|e| DeliveryError::new(e, input))
}

fn answer(
    d: &DeliveryInput,
    club: &ClubSpec,
    equipment: &Equipment,
    predictor: Predictor<'_>,
) -> Result<Answer, DeliveryError> {
    let state = state_of(d, club, equipment)?;
    let metrics = DeliveryMetrics::from_state(&state, club);
    let hand = d.handedness.unwrap_or_default();
    let err = |e| DeliveryError::new(e, d);
    let (model, every) = match predictor {
        Predictor::Plain(m) => (m, 0),
        Predictor::Traced(m) => (m, 10),
    };
    let run = model.run(&state, equipment, &RunOptions { trace_every: every }).map_err(err)?;
    let (course_summary, trace) = match run.course {
        Some(c) => (c.summary, Some(c.trace)),
        None => (Fields::default(), None),
    };
    Ok(Answer {
        output: PredictOutput::new(&run.launch, &metrics, hand, equipment),
        reports: run.report.into(),
        course_summary,
        trace,
    })
}

/// Answers every line of `input` on `out` (`impactd predict`); a bad line is answered with its error on `out` and
/// reported on `err`. Fields of a line that are not a delivery's (labels such as `player`, `club`, `tags`, a
/// previous tool's output) are kept: each answer carries them after its own fields.
pub fn run(
    club: &ClubSpec,
    predictor: Predictor<'_>,
    input: impl BufRead,
    out: impl Write,
    err: impl Write,
) -> Result<Tally, JsonlError> {
    run_models(club, &[predictor], input, out, err)
}

/// As [`run`], with each line answered by every model in turn (`predict --model both`): one answer line per
/// model, each naming its `model`, when there is more than one.
pub fn run_models(
    club: &ClubSpec,
    predictors: &[Predictor<'_>],
    input: impl BufRead,
    out: impl Write,
    err: impl Write,
) -> Result<Tally, JsonlError> {
    let equipment = Equipment::new(club.clone());
    crate::jsonl::process_many("impactd predict", input, out, err, |line: Map<String, Value>| {
        let d: DeliveryInput = serde_json::from_value(Value::Object(line.clone())).map_err(DeliveryError::Input)?;
        let mut answers = Vec::with_capacity(predictors.len());
        for &predictor in predictors {
            let answer = answer(&d, club, &equipment, predictor)?;
            let Value::Object(mut fields) = serde_json::to_value(answer).map_err(DeliveryError::Input)? else {
                return Err(DeliveryError::NotAnObject);
            };
            if predictors.len() > 1 {
                fields.insert("model".into(), Value::String(predictor.model().name().to_string()));
            }
            crate::jsonl::pass_through(line.clone(), &mut fields, &DeliveryInput::FIELDS);
            answers.push(fields);
        }
        Ok(answers)
    })
}

impl Predictor<'_> {
    /// The model that answers.
    pub fn model(&self) -> &dyn ImpactModel {
        match *self {
            Predictor::Plain(m) | Predictor::Traced(m) => m,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::{ImpulseModel, ImpulseVariant};

    /// Good lines are answered; a bad one is answered with the field it is about and does not stop the others.
    #[test]
    fn bad_lines_name_their_field_and_do_not_stop_the_others() {
        let input = concat!(
            "{\"club_speed_mph\":113,\"dynamic_loft_deg\":13,\"attack_angle_deg\":-1.3}\n",
            "\n",
            "{\"club_speed_mph\":500}\n",
            "{\"impact_h_mm\":200,\"club_speed_mph\":100}\n",
        );
        let model = ImpulseModel::new(ImpulseVariant::Adjusted);
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let tally = run(&ClubSpec::driver(), Predictor::Plain(&model), input.as_bytes(), &mut out, &mut err).unwrap();
        assert_eq!(tally, Tally { answered: 1, rejected: 2 });
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<serde_json::Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        // The seed's driver with the adjusted model (Tables 3.1 and 3.3), as in the crate's example: 163.96 mph.
        assert!((lines[0]["ball_speed_mph"].as_f64().unwrap() - 163.957).abs() < 1e-3);
        assert_eq!(lines[1]["line"], 3);
        assert!(lines[1]["error"].as_str().unwrap().starts_with("field `club_speed_mph`"));
        assert_eq!(lines[2]["line"], 4);
        assert!(lines[2]["error"].as_str().unwrap().starts_with("fields `impact_h_mm`/`impact_v_mm`"));
        assert!(String::from_utf8(err).unwrap().starts_with("impactd predict: line 3: field `club_speed_mph`"));
    }

    /// Fields that are not a delivery's are kept, not refused; a field the answer writes itself is the answer's.
    #[test]
    fn unknown_fields_pass_through() {
        let input = "{\"club_speed_mph\":113,\"player\":\"ann\",\"tags\":[\"fit\"],\"ball_speed_mph\":1}\n";
        let model = ImpulseModel::new(ImpulseVariant::Adjusted);
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let tally = run(&ClubSpec::driver(), Predictor::Plain(&model), input.as_bytes(), &mut out, &mut err).unwrap();
        assert_eq!(tally, Tally { answered: 1, rejected: 0 });
        let line: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(line["player"], "ann");
        assert_eq!(line["tags"][0], "fit");
        assert!(line["ball_speed_mph"].as_f64().unwrap() > 100.0, "{line}");
        assert!(line.get("club_speed_mph").is_none(), "{line}");
    }

    /// Regression: `predict --model both` was refused while listed. Each line is answered once per model, each
    /// answer naming its model.
    #[test]
    fn each_line_is_answered_by_each_model() {
        let (standard, adjusted) =
            (ImpulseModel::new(ImpulseVariant::Standard), ImpulseModel::new(ImpulseVariant::Adjusted));
        let predictors = [Predictor::Plain(&standard), Predictor::Plain(&adjusted)];
        let input = "{\"club_speed_mph\":113,\"player\":\"ann\"}\n{\"club_speed_mph\":500}\n";
        let (mut out, mut err) = (Vec::new(), Vec::new());
        let tally = run_models(&ClubSpec::driver(), &predictors, input.as_bytes(), &mut out, &mut err).unwrap();
        assert_eq!(tally, Tally { answered: 1, rejected: 1 });
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<serde_json::Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        assert_eq!(lines.len(), 3, "{text}");
        assert_eq!(lines[0]["model"], standard.name());
        assert_eq!(lines[1]["model"], adjusted.name());
        assert_eq!(lines[1]["player"], "ann");
        assert_ne!(lines[0]["ball_speed_mph"], lines[1]["ball_speed_mph"]);
        assert_eq!(lines[2]["line"], 2);
    }
}
