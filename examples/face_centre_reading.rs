//! TrackMan's dynamic loft and face angle (the contact point's, by TrackMan's definitions) turned into the face
//! centre's on a club's face, as `compare --by-club` reads them (`offline::identify::trackman_reading`), for
//! deliveries typed or built by a script: JSON lines of deliveries in (stdin), the same deliveries with the face
//! centre's loft and face out (stdout), so that `impactd predict` runs them as `compare --by-club` would. Usage:
//! `cargo run --release --example face_centre_reading -- driver < deliveries.jsonl`.

use std::io::{BufRead, Write};

use impactd::equipment::load_club;
use impactd::impact::Equipment;
use impactd::offline::identify::trackman_reading::at_face_centre;
use impactd::wire::DeliveryInput;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let club = std::env::args().nth(1).unwrap_or_else(|| "driver".to_string());
    let equipment = Equipment::new(load_club(&club)?.club);
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    for (i, line) in std::io::stdin().lock().lines().enumerate() {
        let line = line?;
        if line.trim().is_empty() {
            continue;
        }
        let d: DeliveryInput = serde_json::from_str(&line).map_err(|e| format!("line {}: {e}", i + 1))?;
        let read = at_face_centre(&d, &equipment).map_err(|e| format!("line {}: {e}", i + 1))?;
        writeln!(out, "{}", serde_json::to_string(&read)?)?;
    }
    Ok(())
}
