//! Value parsers for every flag that becomes a duration, a rate or a count: a NaN, an infinity, a negative or
//! an absurd value is refused by clap with the flag named, before any work starts (so none of them can reach a
//! `Duration` constructor that panics, a loop that never ends or an allocation that cannot succeed).

use std::time::Duration;

/// The most shots, swings or samples a command is asked for in one run.
pub const MAX_COUNT: u64 = 1_000_000;
/// The longest duration a flag may give (a day).
pub const MAX_SECONDS: f64 = 86_400.0;

fn number(text: &str) -> Result<f64, String> {
    let v: f64 = text.trim().parse().map_err(|_| format!("`{text}` is not a number"))?;
    if !v.is_finite() {
        return Err(format!("`{text}` is not a finite number"));
    }
    Ok(v)
}

/// A positive duration in seconds, at most a day, that a `Duration` can hold.
pub fn seconds(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if !(v > 0.0 && v <= MAX_SECONDS) || Duration::try_from_secs_f64(v).is_err() {
        return Err(format!("{v} s is not a duration within 0 and {MAX_SECONDS} s"));
    }
    Ok(v)
}

/// A duration in seconds that may be 0.
#[cfg(feature = "daemon")]
pub fn seconds_or_zero(text: &str) -> Result<f64, String> {
    match number(text)? {
        0.0 => Ok(0.0),
        _ => seconds(text),
    }
}

/// A capture rate of a motion-capture rig (Hz).
pub fn capture_rate_hz(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if !(60.0..=10_000.0).contains(&v) {
        return Err(format!("{v} Hz is not a capture rate within 60 and 10000 Hz"));
    }
    Ok(v)
}

/// The slowest replay pace: a thousandth of real time (a second of samples in about 17 minutes).
#[cfg(feature = "daemon")]
pub const MIN_PACE: f64 = 1e-3;

/// A multiple of real time (replay pace), at least [`MIN_PACE`]: a smaller one would wait longer between two
/// samples than any replay is watched.
#[cfg(feature = "daemon")]
pub fn pace(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if !(MIN_PACE..=1e6).contains(&v) {
        return Err(format!("{v} is not a multiple of real time within {MIN_PACE} and 1000000"));
    }
    Ok(v)
}

/// A noise level or other non-negative magnitude, at most `1e3` of its unit.
pub fn magnitude(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if !(0.0..=1e3).contains(&v) {
        return Err(format!("{v} is not within 0 and 1000"));
    }
    Ok(v)
}

/// A probability.
pub fn probability(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if !(0.0..=1.0).contains(&v) {
        return Err(format!("{v} is not a probability within 0 and 1"));
    }
    Ok(v)
}

fn integer(text: &str) -> Result<u64, String> {
    text.trim().parse().map_err(|_| format!("`{text}` is not a whole number"))
}

/// A count of at least 1 and at most [`MAX_COUNT`].
pub fn count(text: &str) -> Result<u64, String> {
    match integer(text)? {
        v @ 1..=MAX_COUNT => Ok(v),
        v => Err(format!("{v} is not a count within 1 and {MAX_COUNT}")),
    }
}

/// A count that may be 0 (a meaning of its own: none, or until stopped), at most [`MAX_COUNT`].
pub fn count_or_zero(text: &str) -> Result<u64, String> {
    match integer(text)? {
        v @ 0..=MAX_COUNT => Ok(v),
        v => Err(format!("{v} is not a count within 0 and {MAX_COUNT}")),
    }
}

/// [`count`] as a `usize`.
pub fn count_usize(text: &str) -> Result<usize, String> {
    count(text).and_then(|v| usize::try_from(v).map_err(|e| e.to_string()))
}

/// [`count_or_zero`] as a `usize`.
pub fn count_or_zero_usize(text: &str) -> Result<usize, String> {
    count_or_zero(text).and_then(|v| usize::try_from(v).map_err(|e| e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_would_panic_or_run_away_is_refused() {
        for bad in ["NaN", "inf", "-1", "0", "1e300", "x"] {
            assert!(seconds(bad).is_err(), "{bad}");
            assert!(pace(bad).is_err(), "{bad}");
        }
        assert!(pace("1e-12").is_err() && pace("0.001").is_ok() && pace("1000000").is_ok());
        assert!(capture_rate_hz("NaN").is_err() && capture_rate_hz("720").is_ok());
        assert!(magnitude("NaN").is_err() && magnitude("0").is_ok());
        assert!(count("18446744073709551615").is_err() && count("0").is_err() && count("5").is_ok());
        assert!(count_or_zero("0").is_ok() && count_or_zero("18446744073709551615").is_err());
        assert_eq!(seconds_or_zero("0"), Ok(0.0));
        assert!(seconds_or_zero("NaN").is_err());
    }
}
