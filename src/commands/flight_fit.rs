//! `impactd flight-fit`: refits the flight model's coefficients to the TrackMan tour averages, shows the fit and
//! cross-validates it leaving one club out at a time.

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;
use impactd::flight::{cv, fit};

#[derive(Debug, Args)]
pub struct FlightFitArgs {
    /// Nelder-Mead iterations per restart, from `flight::fit::START`, before the minimax stage (0: show the
    /// errors of `Aero::FITTED`).
    #[arg(long, default_value_t = fit::ITERATIONS)]
    pub iterations: usize,
    /// Skip the leave-one-club-out cross-validation (twelve more fits).
    #[arg(long)]
    pub no_cv: bool,
    /// One JSON object (coefficients, per-club errors, cross-validation) instead of tables.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &FlightFitArgs) -> Result<ExitCode> {
    let (iterations, json) = (args.iterations, args.json);
    let rows = fit::parse_table(fit::TRACKMAN_CSV).context("TrackMan table")?;
    let current = impactd::flight::Aero::FITTED;
    let (aero, cost, worst) = if iterations == 0 {
        (current, fit::cost(&current, &rows), fit::worst(&current, &rows))
    } else {
        if !json {
            eprintln!("fitting from fit::START ({iterations} Nelder-Mead iterations per restart, then minimax)...");
        }
        let f = fit::fit(&rows, &fit::START, iterations, |step| match step {
            fit::Step::Run(run, cost) if !json => eprintln!("Nelder-Mead run {run}: cost {cost:.4}"),
            fit::Step::Minimax(i, worst) if !json => eprintln!("minimax {i}: largest scaled error {worst:.6}"),
            _ => {}
        });
        (f.aero, f.cost, f.worst)
    };
    let clubs = cv::club_errors(&aero, &rows);
    let validation = if args.no_cv {
        None
    } else {
        if !json {
            eprintln!("leave-one-club-out: twelve fits of eleven clubs...");
        }
        Some(cv::leave_one_out(&rows, iterations.max(fit::ITERATIONS), |h| {
            if !json {
                eprintln!("  without {}: carry {:+.2} %", h.club, h.carry_error_pct);
            }
        }))
    };
    if json {
        let out = serde_json::json!({
            "aero": aero,
            "largest_scaled_error": worst,
            "cost": cost,
            "clubs": clubs,
            "within_4yd_3yd_3deg": clubs.iter().filter(|c| c.within(4.0, 3.0, 3.0)).count(),
            "within_3yd_2yd_2deg": clubs.iter().filter(|c| c.within(3.0, 2.0, 2.0)).count(),
            "cross_validation": validation,
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{} (largest error {:.4} of its target, cost {cost:.4}): {aero:?}",
        if iterations == 0 { "current" } else { "fitted" },
        worst
    );
    println!("{:<8} {:>15} {:>13} {:>14}  within 3/2/2", "club", "carry yd", "apex yd", "land deg");
    for c in &clubs {
        println!(
            "{:<8} {:>6.1} ({:+6.2}) {:>5.1} ({:+5.2}) {:>5.1} ({:+5.2})  {}",
            c.club,
            c.carry_yd,
            c.carry_error_yd,
            c.apex_yd,
            c.apex_error_yd,
            c.land_angle_deg,
            c.land_angle_error_deg,
            if c.within(3.0, 2.0, 2.0) { "yes" } else { "no" }
        );
    }
    for (lim, name) in [
        ((4.0, 3.0, 3.0), "carry 4 yd, apex 3 yd, land angle 3 deg"),
        ((3.0, 2.0, 2.0), "carry 3 yd, apex 2 yd, land angle 2 deg"),
    ] {
        let n = clubs.iter().filter(|c| c.within(lim.0, lim.1, lim.2)).count();
        println!("{n} of {} clubs within {name}", clubs.len());
    }
    if let Some(v) = validation {
        println!("leave-one-club-out (each club predicted by a fit to the other eleven):");
        println!("{:<8} {:>10} {:>10} {:>9} {:>9}", "club", "carry %", "carry yd", "apex yd", "land deg");
        for h in &v.holdouts {
            println!(
                "{:<8} {:>+10.2} {:>10.1} {:>+9.2} {:>+9.2}",
                h.club, h.carry_error_pct, h.predicted_carry_yd, h.apex_error_yd, h.land_angle_error_deg
            );
        }
        println!(
            "largest: carry {:.2} %, apex {:.2} yd, land angle {:.2} deg",
            v.max_carry_error_pct, v.max_apex_error_yd, v.max_land_angle_error_deg
        );
    }
    Ok(ExitCode::SUCCESS)
}
