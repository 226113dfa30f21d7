//! Uneekor's fields, units and 99999 against impactd's conventions, on `tests/data/uneekor/signs-driver.csv` (the
//! same strikes as the Foresight fixture, made up in the report API's field names and units).

use super::*;

const SIGNS: &str = include_str!("../../../tests/data/uneekor/signs-driver.csv");

#[test]
fn each_sign_and_not_captured_reads_in_impactds_convention() {
    assert!(is_uneekor_csv(SIGNS));
    let (rows, skipped) = read_labelled(SIGNS).unwrap();
    assert_eq!(skipped, SkippedRows { without_club_or_ball: 1, incomplete_club_data: 1 });
    assert_eq!(rows.len(), 6);
    let d = |k: usize| &rows[k].0.delivery;
    let m = |k: usize| &rows[k].0.measured;
    // m/s to mph, m to yd.
    assert!((d(0).club_speed_mph - 103.0).abs() < 1e-3, "{}", d(0).club_speed_mph);
    assert!((m(0).ball_speed_mph - 150.0).abs() < 1e-3);
    assert!((m(0).carry_yd.unwrap() - 250.0).abs() < 1e-3);
    // impact_x + toe (impactd's h + toe), side_spin - a draw, side_angle + right.
    assert_eq!((d(1).impact_h_mm, m(1).sidespin_rpm, m(1).launch_direction_deg), (15.0, -400.0, 1.5));
    assert_eq!((d(2).impact_h_mm, m(2).sidespin_rpm, m(2).launch_direction_deg), (-12.0, 350.0, -1.2));
    assert_eq!(d(3).impact_v_mm, 8.0);
    assert_eq!((d(4).club_path_deg, d(4).face_angle_deg, d(4).attack_angle_deg), (3.0, 2.0, 1.5));
    // 99999 in the impact location: read at the face centre, unlocated.
    assert_eq!((d(5).impact_h_mm, d(5).impact_v_mm), (0.0, 0.0));
    assert!(!rows[5].1.impact_located && rows[..5].iter().all(|(_, l)| l.impact_located));
    assert!(rows.iter().all(|(_, l)| l.club.as_deref() == Some("driver")));
}

#[test]
fn bracketed_units_convert_and_unknown_ones_are_errors() {
    let mph = SIGNS.replacen("ball_speed,", "ball_speed (mph),", 1);
    let (rows, _) = read_labelled(&mph).unwrap();
    assert_eq!(rows[0].0.measured.ball_speed_mph, 67.056);
    let e = read_labelled(&SIGNS.replacen("club_speed,", "club_speed (knots),", 1)).unwrap_err().to_string();
    assert!(e.contains("club_speed (knots)") && e.contains("knots"), "{e}");
    let e = read_labelled(&SIGNS.replacen(",dynamic_loft,", ",loft,", 1)).unwrap_err().to_string();
    assert!(e.contains("no column `dynamic_loft`"), "{e}");
}
