//! Each sign convention of Foresight's export against impactd's, on `tests/data/foresight/signs-driver.csv` (one
//! strike per row, made up in the export's layout), and the header errors.

use super::*;

const SIGNS: &str = include_str!("../../../tests/data/foresight/signs-driver.csv");

#[test]
fn each_sign_reads_in_impactds_convention() {
    assert!(is_foresight_csv(SIGNS));
    let (rows, skipped) = read_labelled(SIGNS).unwrap();
    // The sentinel club speed (9999.9) is no club data; the row without a club path has incomplete club data.
    assert_eq!(skipped, SkippedRows { without_club_or_ball: 1, incomplete_club_data: 1 });
    assert_eq!(rows.len(), 6);
    let d = |k: usize| &rows[k].0.delivery;
    let m = |k: usize| &rows[k].0.measured;
    // Centre, square.
    assert_eq!((d(0).impact_h_mm, d(0).impact_v_mm, d(0).face_angle_deg, d(0).club_path_deg), (0.0, 0.0, 0.0, 0.0));
    assert_eq!((d(0).club_speed_mph, d(0).attack_angle_deg, d(0).dynamic_loft_deg), (103.0, 2.0, Some(14.0)));
    assert_eq!(
        (m(0).ball_speed_mph, m(0).launch_angle_deg, m(0).backspin_rpm, m(0).carry_yd),
        (150.0, 12.0, 2500.0, Some(250.0))
    );
    // Foresight's toe- is impactd's toward-the-toe +; its L- side spin a draw (sidespin -), its R+ push right +.
    assert_eq!(d(1).impact_h_mm, 15.0);
    assert_eq!((m(1).sidespin_rpm, m(1).launch_direction_deg), (-400.0, 1.5));
    // Heel + is impactd's toward the heel (-); R+ side spin a fade (+), L- pull left (-).
    assert_eq!(d(2).impact_h_mm, -12.0);
    assert_eq!((m(2).sidespin_rpm, m(2).launch_direction_deg), (350.0, -1.2));
    // High + and low - up the face as impactd's v.
    assert_eq!((d(3).impact_v_mm, d(4).impact_v_mm), (8.0, -6.0));
    // In-to-out + is a path to the right (+), open + a face to the right (+).
    assert_eq!((d(5).club_path_deg, d(5).face_angle_deg, d(5).attack_angle_deg), (3.0, 2.0, 1.5));
    assert!(rows.iter().all(|(_, l)| l.club.as_deref() == Some("Dr") && l.spin_measured && l.axis_measured));
    assert!(rows.iter().all(|(_, l)| l.impact_located));
    assert!(rows.iter().all(|(line, _)| line.delivery.dynamic_lie_deg.is_none()));
}

#[test]
fn metric_units_convert_and_unknown_units_or_signs_are_errors() {
    let metric = SIGNS.replacen("Ball Speed (mph)", "Ball Speed (km/h)", 1).replacen("Carry (yds)", "Carry (m)", 1);
    let (rows, _) = read_labelled(&metric).unwrap();
    assert!((rows[0].0.measured.ball_speed_mph - 150.0 / 1.609344).abs() < 1e-9);
    assert!((rows[0].0.measured.carry_yd.unwrap() - 250.0 / 0.9144).abs() < 1e-9);
    let knots = SIGNS.replacen("Club Speed (mph)", "Club Speed (knots)", 1);
    let e = read_labelled(&knots).unwrap_err().to_string();
    assert!(e.contains("Club Speed (knots)") && e.contains("knots"), "{e}");
    let flipped = SIGNS.replacen("(mm toe-/heel+)", "(mm toe+/heel-)", 1);
    let e = read_labelled(&flipped).unwrap_err().to_string();
    assert!(e.contains("Face Impact Horizontal") && e.contains("toe+/heel-") && e.contains("toe-/heel+"), "{e}");
    let no_loft = SIGNS.replacen("Loft (deg)", "Static Loft (deg)", 1);
    let e = read_labelled(&no_loft).unwrap_err().to_string();
    assert!(e.contains("no column `Loft"), "{e}");
    let bad = SIGNS.replacen("147.0,12.2", "fast,12.2", 1);
    let e = read_labelled(&bad).unwrap_err().to_string();
    assert!(e.contains("row 3") && e.contains("Ball Speed (mph)") && e.contains("fast"), "{e}");
}
