//! `impactd replay --pause`: stdin controls a replay's pause switch, like rosbag2's `play` (space pauses and
//! resumes, `--start-paused`).
//!
//! - On a terminal, one key is enough: space or Enter pauses and resumes, Ctrl-C stops (exit 130). The terminal
//!   is put in non-canonical, no-echo mode with `stty` for the replay and restored when it ends; when `stty`
//!   cannot, lines are read as below (Enter toggles).
//! - Otherwise stdin is read as lines: `pause`, `resume`, or `toggle` (an empty line toggles too); anything else
//!   is reported and ignored. When stdin ends, a paused replay resumes, so a replay never waits on a closed input.
//!
//! Each change is reported on stderr with the capture time reached (`paused at 3.20 s`, `resumed at 3.20 s`).

use std::io::{BufRead, IsTerminal, Read};
use std::process::{Command, Stdio};
use std::sync::Arc;

use impactd::daemon::replay::PauseControl;

/// Restores the terminal's mode when the replay ends.
pub struct TerminalMode {
    saved: Option<String>,
}

impl Drop for TerminalMode {
    fn drop(&mut self) {
        if let Some(saved) = self.saved.take() {
            restore(&saved);
        }
    }
}

fn stty(args: &[&str]) -> Option<String> {
    let out = Command::new("stty").args(args).stdin(Stdio::inherit()).stderr(Stdio::null()).output().ok()?;
    out.status.success().then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn restore(saved: &str) {
    let _ = stty(&[saved]);
}

fn report(control: &PauseControl, hint: &str) {
    if control.is_paused() {
        eprintln!("paused at {:.2} s of capture time ({hint})", control.position_s());
    } else {
        eprintln!("resumed at {:.2} s of capture time", control.position_s());
    }
}

/// Starts reading stdin for `control`; the returned guard puts the terminal back as it was.
pub fn start(control: Arc<PauseControl>) -> TerminalMode {
    let terminal = std::io::stdin().is_terminal();
    let saved = if terminal { stty(&["-g"]) } else { None };
    // Ctrl-C arrives as a byte (no signal), so that the terminal is restored before the process exits.
    let raw = saved.as_ref().is_some_and(|_| stty(&["-icanon", "-echo", "-isig", "min", "1"]).is_some());
    if raw {
        eprintln!("space or Enter pauses and resumes the replay; Ctrl-C stops it");
        if control.is_paused() {
            eprintln!("paused at the start (space or Enter resumes)");
        }
        let saved = saved.unwrap_or_default();
        let restore_to = saved.clone();
        std::thread::spawn(move || keys(&control, &restore_to));
        TerminalMode { saved: Some(saved) }
    } else {
        if let Some(s) = &saved {
            restore(s);
        }
        if control.is_paused() {
            eprintln!("paused at the start (a line `resume` or `toggle` on stdin resumes)");
        }
        std::thread::spawn(move || lines(&control, std::io::stdin().lock()));
        TerminalMode { saved: None }
    }
}

/// One key at a time from a terminal in non-canonical mode.
fn keys(control: &PauseControl, saved: &str) {
    let mut stdin = std::io::stdin().lock();
    let mut byte = [0u8; 1];
    while let Ok(1) = stdin.read(&mut byte) {
        match byte[0] {
            b' ' | b'\n' | b'\r' => {
                control.toggle();
                report(control, "space or Enter resumes");
            }
            // Ctrl-C.
            3 => {
                restore(saved);
                eprintln!("stopped at {:.2} s of capture time", control.position_s());
                std::process::exit(130);
            }
            _ => {}
        }
    }
}

/// What a line of stdin asks for: `Some(true)` pause, `Some(false)` resume, `None` toggle; `Err` not a command.
pub fn command(line: &str) -> Result<Option<bool>, String> {
    match line.trim() {
        "pause" => Ok(Some(true)),
        "resume" => Ok(Some(false)),
        "toggle" | "" => Ok(None),
        other => Err(format!("stdin: '{other}' is not a command (pause, resume, toggle or an empty line)")),
    }
}

/// Commands, one per line, until the input ends; then a paused replay resumes.
pub fn lines(control: &PauseControl, input: impl BufRead) {
    for line in input.lines() {
        let Ok(line) = line else { break };
        match command(&line) {
            Ok(Some(paused)) => {
                if control.set(paused) {
                    report(control, "`resume` resumes");
                }
            }
            Ok(None) => {
                control.toggle();
                report(control, "`resume` resumes");
            }
            Err(e) => eprintln!("{e}"),
        }
    }
    if control.set(false) {
        eprintln!("stdin closed: resumed at {:.2} s of capture time", control.position_s());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_commands() {
        assert_eq!(command("pause\n"), Ok(Some(true)));
        assert_eq!(command(" resume "), Ok(Some(false)));
        assert_eq!(command(""), Ok(None));
        assert!(command("stop").is_err());
        let control = PauseControl::new(false);
        lines(&control, "pause\nbogus\n".as_bytes());
        assert!(!control.is_paused(), "the end of the input resumes");
    }
}
