//! Every zenoh key expression (no leading `/`, snake_case), each with its payload (ARCHITECTURE.md section 4).

/// In: [`ClubheadSampleMsg`](super::ClubheadSampleMsg) from the rig, `mocap/<rig>/clubhead`.
pub fn clubhead(rig: &str) -> String {
    format!("mocap/{rig}/clubhead")
}
/// Recorded only (never published): [`RejectedInput`](super::RejectedInput), a payload on the rig's clubhead key
/// that was not a usable sample, beside the reason.
pub fn rejected(rig: &str) -> String {
    format!("mocap/{rig}/clubhead/rejected")
}
/// Out of `impactd bridge natnet|qtm`, once a second: [`MocapInputStatus`](super::MocapInputStatus), the
/// health of the native input feeding the rig's clubhead samples.
pub fn mocap_input(rig: &str) -> String {
    format!("mocap/{rig}/input")
}
/// In: [`BallSampleMsg`](super::BallSampleMsg), the tracked ball's centre (lab frame), `mocap/<rig>/ball`; a
/// ball at rest sets the position of the rig's next impact. Recorded.
pub fn ball(rig: &str) -> String {
    format!("mocap/{rig}/ball")
}
/// Every rig's clubhead samples.
pub const CLUBHEAD_ALL: &str = "mocap/*/clubhead";
/// Recorded only: [`RejectedInput`](super::RejectedInput)s of samples on the keys of rigs no daemon serves.
pub const UNKNOWN_RIG_REJECTED: &str = "impactd/unknown_rig/rejected";
/// Every rig's predictions.
pub const LAUNCH_ALL: &str = "golf/*/launch";
/// Every synthetic rig's truth.
pub const TRUTH_ALL: &str = "sim/*/truth";
/// Out: [`ImpactMessage`](super::ImpactMessage), the estimated state at impact.
pub fn impact(rig: &str) -> String {
    format!("golf/{rig}/impact")
}
/// Out: [`LaunchPrediction`](super::LaunchPrediction).
pub fn launch(rig: &str) -> String {
    format!("golf/{rig}/launch")
}
/// Out, right after each launch: [`FlightLine`](super::FlightLine), the points of its predicted flight.
pub fn flight(rig: &str) -> String {
    format!("golf/{rig}/flight")
}
/// Out, once a second: [`StatusMessage`](super::StatusMessage).
pub fn status(rig: &str) -> String {
    format!("golf/{rig}/status")
}
/// Liveliness token of the daemon serving a rig.
pub fn alive(rig: &str) -> String {
    format!("golf/{rig}/impactd/alive")
}
/// Liveliness token of one daemon serving a rig (`zid`: its zenoh id), watched by the others so that two daemons
/// on one rig say so.
pub fn daemon_token(rig: &str, zid: &str) -> String {
    format!("golf/{rig}/impactd/daemon/{zid}")
}
/// Queryable of the daemon serving a rig: a daemon about to serve it too asks who serves it (payload `{"from":
/// {"zid", "pid", "version"}, "take_over": bool}`) and is answered `{"from": {...}, "handing_over": bool}`; with
/// `take_over` the daemon serving it stops.
pub fn serve(rig: &str) -> String {
    format!("golf/{rig}/impactd/serve")
}
/// Queryable: the daemon's configuration for the rig (JSON, read-only).
pub fn config(rig: &str) -> String {
    format!("golf/{rig}/impactd/config")
}
/// Out of `impactd sim`: [`TruthMessage`](super::TruthMessage), what the synthetic rig really swung.
pub fn truth(rig: &str) -> String {
    format!("sim/{rig}/truth")
}
/// In: [`MeasuredLaunch`](super::MeasuredLaunch) from a launch monitor (or the Open Connect listener).
pub fn measured_launch(rig: &str) -> String {
    format!("lm/{rig}/launch")
}
/// Out: [`ComparisonMessage`](super::ComparisonMessage), a prediction paired with its measurement.
pub fn comparison(rig: &str) -> String {
    format!("golf/{rig}/comparison")
}
/// Recorded (MCAP only): [`OpenConnectTraffic`](super::OpenConnectTraffic) to and from the rig's simulator.
pub fn simulator_traffic(rig: &str) -> String {
    format!("golf/{rig}/simulator")
}
/// Recorded (MCAP only): [`OpenConnectTraffic`](super::OpenConnectTraffic) of the rig's Open Connect listener.
pub fn launch_monitor_traffic(rig: &str) -> String {
    format!("lm/{rig}/open_connect")
}
/// Recorded and in the live view: the club's pose in the world at each sample (Foxglove `PoseInFrame`).
pub fn foxglove_club_pose(rig: &str) -> String {
    format!("foxglove/{rig}/club_pose")
}
/// Recorded and in the live view: ball and club at each impact (Foxglove `SceneUpdate`).
pub fn foxglove_impact_scene(rig: &str) -> String {
    format!("foxglove/{rig}/impact_scene")
}
/// Recorded and in the live view: the predicted ball flight as a line strip (Foxglove `SceneUpdate`).
pub fn foxglove_ball_flight(rig: &str) -> String {
    format!("foxglove/{rig}/ball_flight")
}
/// In: [`ShotLabels`](super::ShotLabels), the labels (player, club, tags, note) of the rig's shots from now on;
/// each put replaces the labels before it. Recorded.
pub fn session(rig: &str) -> String {
    format!("golf/{rig}/session")
}
/// In: a rig's club from now on, as plain UTF-8 text: a preset name (`iron7`) or a club file's path. A bad put is
/// logged and changes nothing. Recorded (and so out, in recordings): [`ClubChange`](super::ClubChange) at start
/// and at every change, by a put or by another tracked body (`[rig.clubs]`).
pub fn club(rig: &str) -> String {
    format!("golf/{rig}/club")
}
/// In: [`ShotExclusion`](super::ShotExclusion), a shot left out of (or taken back into) the session's numbers.
/// Recorded, so `impactd session` leaves it out too.
pub fn exclude(rig: &str) -> String {
    format!("golf/{rig}/exclude")
}
/// In: [`DisplaySettings`](super::DisplaySettings), the units the rig's bay screens show.
pub fn display(rig: &str) -> String {
    format!("golf/{rig}/display")
}
/// Every rig's shot exclusions.
pub const EXCLUDE_ALL: &str = "golf/*/exclude";
/// Every rig's display settings.
pub const DISPLAY_ALL: &str = "golf/*/display";
/// The rig name of a `golf/<rig>/<leaf>` key.
pub fn rig_of_golf<'a>(key: &'a str, leaf: &str) -> Option<&'a str> {
    let rest = key.strip_prefix("golf/")?;
    let rig = rest.strip_suffix(leaf)?.strip_suffix('/')?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// Every rig's session labels.
pub const SESSION_ALL: &str = "golf/*/session";
/// The rig name of a `golf/<rig>/session` key.
pub fn rig_of_session(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("golf/")?;
    let rig = rest.strip_suffix("/session")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// The rig name of a `golf/<rig>/club` key.
pub fn rig_of_club(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("golf/")?;
    let rig = rest.strip_suffix("/club")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// The rig name of a `sim/<rig>/truth` key.
pub fn rig_of_truth(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("sim/")?;
    let rig = rest.strip_suffix("/truth")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// The rig name of a `golf/<rig>/launch` key.
pub fn rig_of_launch(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("golf/")?;
    let rig = rest.strip_suffix("/launch")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// The rig name of a `mocap/<rig>/clubhead` key.
pub fn rig_of_clubhead(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("mocap/")?;
    let rig = rest.strip_suffix("/clubhead")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// The rig name of a `mocap/<rig>/ball` key.
pub fn rig_of_ball(key: &str) -> Option<&str> {
    let rest = key.strip_prefix("mocap/")?;
    let rig = rest.strip_suffix("/ball")?;
    (!rig.is_empty() && !rig.contains('/')).then_some(rig)
}
/// Whether a rig name can stand in a key expression.
pub fn valid_rig_name(rig: &str) -> bool {
    !rig.is_empty() && rig.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}
