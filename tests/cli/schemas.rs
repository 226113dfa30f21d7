//! Every message type's JSON Schema in `schemas/` matches the Rust types. Regenerate with
//! `cargo run -- schemas -o schemas` (or run this test with UPDATE_SCHEMAS=1) after changing a type.

#![allow(clippy::unwrap_used)]

#[test]
fn schemas_match_the_types() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas");
    let update = std::env::var_os("UPDATE_SCHEMAS").is_some();
    let mut drifted = Vec::new();
    for (name, schema) in impactd::wire::schemas() {
        let path = dir.join(format!("{name}.json"));
        if update {
            std::fs::write(&path, &schema).unwrap();
        }
        match std::fs::read_to_string(&path) {
            Ok(on_disk) if on_disk == schema => {}
            _ => drifted.push(name),
        }
    }
    assert!(drifted.is_empty(), "schemas/ is out of date for {drifted:?}: run `cargo run -- schemas -o schemas`");
    // A sample as the README documents it validates against the types.
    let sample = r#"{"rig":"bay1","frame":1,"t_ns":1000,"position_m":[0.1,0.2,0.3],"orientation":{"x":0.0,"y":0.0,"z":0.0,"w":1.0},"occluded":false}"#;
    assert!(impactd::wire::parse_sample("bay1", sample.as_bytes(), "application/json").is_ok());
}
