//! `impactd map` draws a picture a person can put in a report: only the face (cells clipped to the outline),
//! round ticks through 0, a colour bar labelled along its length, a palette diverging from zero for signed
//! metrics, the delivery in the title; and an error, not a blank picture, when nothing can be drawn.

#![allow(clippy::unwrap_used)]

use std::process::{Command, Output, Stdio};

fn impactd(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impactd")).args(args).stdin(Stdio::null()).output().unwrap()
}

/// The texts of the SVG's `<text>` elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text").skip(1).filter_map(|t| Some(t.split_once('>')?.1.split_once("</text>")?.0.to_string())).collect()
}

#[test]
fn the_map_is_a_report_picture() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("map.svg");
    let args = ["map", "--club", "iron7", "--metric", "sidespin", "--club-speed-mph", "85", "--attack-angle-deg=-4"];
    let out = impactd(&[&args[..], &["-o", svg.to_str().unwrap()]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&svg).unwrap();
    let labels = texts(&text);
    // The delivery in the title.
    assert!(labels.iter().any(|t| t.contains("club 85 mph, attack -4.0°") && t.contains("dynamic loft")), "{labels:?}");
    // Only the face: the cells are clipped to the outline, which is drawn.
    assert!(text.contains(r#"<clipPath id="outline"><polygon"#) && text.contains(r#"clip-path="url(#outline)""#));
    assert!(labels.iter().any(|t| t == "face centre") && labels.iter().any(|t| t.starts_with("CG")));
    // Signed metric: a diverging scale symmetric about 0, whose middle colour (near-white) is 0, labelled at
    // round values along the bar; 0 appears as an axis tick too (at least three "0" labels: x, y, bar).
    let numbers: Vec<f64> = labels.iter().filter_map(|t| t.parse().ok()).collect();
    assert!(labels.iter().filter(|t| *t == "0").count() >= 3, "{labels:?}");
    let bar: Vec<f64> = numbers.iter().copied().filter(|v| v.abs() >= 100.0).collect();
    assert!(bar.len() >= 4, "colour bar ticks {labels:?}");
    assert!(bar.iter().all(|v| v % 100.0 == 0.0), "round ticks {bar:?}");
    let (lo, hi) = bar.iter().fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    assert_eq!(lo, -hi, "symmetric about zero");
    assert!(text.contains(r##"<stop offset="0.5" stop-color="#f7f7f7"/>"##));
    assert!(labels.iter().any(|t| t == "sidespin (rpm, + fade/slice)"));
    // An unsigned metric uses the sequential palette (no white middle).
    let out = impactd(&["map", "--club", "iron7", "--metric", "carry", "-o", svg.to_str().unwrap()]);
    assert!(out.status.success());
    assert!(!std::fs::read_to_string(&svg).unwrap().contains("#f7f7f7"));
}

/// A model that cannot predict any point of the face is an error (exit 2, the reason, no file).
#[test]
fn nothing_to_draw_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("map.svg");
    let out = impactd(&["map", "--club", "driver", "--model", "ground", "-o", svg.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no impact location on the face has a prediction") && err.contains("flat"), "{err}");
    assert!(!svg.exists());
}
