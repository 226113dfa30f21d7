//! A rig's session as a download: the kept predictions in TrackMan's CSV layout, row for row what
//! `impactd export --format trackman-csv` writes from the recording.

use super::feed::Bay;
use crate::session::trackman_csv;

/// The CSV text of `rig`'s session, or `None` for a rig not served.
pub fn session_csv(bay: &Bay, rig: &str) -> Option<Vec<u8>> {
    let states = bay.states.lock().ok()?;
    let state = states.get(rig)?;
    let comparisons: Vec<crate::wire::ComparisonMessage> =
        state.comparisons().filter_map(|c| serde_json::from_value(c.clone()).ok()).collect();
    let rows: Vec<Vec<String>> = state
        .shots()
        .iter()
        .map(|p| {
            let t = std::time::UNIX_EPOCH + std::time::Duration::from_nanos(p.t_impact_ns);
            let date = humantime::format_rfc3339_seconds(t).to_string();
            let measured = trackman_csv::measured_for(p, &comparisons);
            trackman_csv::row(p, &bay.recording_name, &date, measured)
        })
        .collect();
    drop(states);
    let mut out = Vec::new();
    trackman_csv::write(&mut out, &rows).ok()?;
    Some(out)
}

/// The rig of a download path `/rig/<rig>/session.csv`.
pub fn rig_of_path(path: &str) -> Option<&str> {
    let rig = path.strip_prefix("/rig/")?.strip_suffix("/session.csv")?;
    crate::wire::keys::valid_rig_name(rig).then_some(rig)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn download_paths_name_a_rig() {
        assert_eq!(rig_of_path("/rig/bay1/session.csv"), Some("bay1"));
        assert_eq!(rig_of_path("/rig/../session.csv"), None);
        assert_eq!(rig_of_path("/rig//session.csv"), None);
        let bay = Bay::new(vec!["bay1".into()], "s.mcap".into(), Default::default());
        assert!(session_csv(&bay, "bay2").is_none());
        let empty = String::from_utf8(session_csv(&bay, "bay1").unwrap()).unwrap();
        assert!(empty.starts_with("sep=,"), "{empty}");
    }
}
