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
    /// The trade-off of a single ball on the table instead: carry and land angle alone fitted (carry scaled by
    /// 4 % of each club's, the land angle by 1-6 deg), the largest carry error each largest land-angle error
    /// costs.
    #[arg(long, conflicts_with = "no_cv")]
    pub tradeoff: bool,
}

pub fn run(args: &FlightFitArgs) -> Result<ExitCode> {
    let (iterations, json) = (args.iterations, args.json);
    let rows = fit::parse_table(fit::TRACKMAN_CSV).context("TrackMan table")?;
    if args.tradeoff {
        return tradeoff(&rows, iterations.max(1), json);
    }
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
            "within_4pct_3yd_3deg": clubs.iter().filter(|c| c.within_pct(4.0, 3.0, 3.0)).count(),
            "max_carry_error_pct": clubs.iter().map(|c| c.carry_error_pct().abs()).fold(0.0, f64::max),
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
    let n = clubs.iter().filter(|c| c.within_pct(4.0, 3.0, 3.0)).count();
    println!("{n} of {} clubs within carry 4 %, apex 3 yd, land angle 3 deg", clubs.len());
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

/// `--tradeoff`: the front of carry against land angle for one ball.
fn tradeoff(rows: &[fit::TourAverage], iterations: usize, json: bool) -> Result<ExitCode> {
    use impactd::flight::tradeoff;
    if !json {
        eprintln!("fitting carry and land angle alone, one fit per land-angle tolerance...");
    }
    let mut points = Vec::new();
    for apex in tradeoff::APEX_YD {
        points.extend(tradeoff::front(rows, iterations, apex, |p| {
            if !json {
                eprintln!("  apex {:?} yd, land angle {:.1} deg: done", p.apex_tolerance_yd, p.land_tolerance_deg);
            }
        }));
    }
    let club = |i: usize| rows.get(i).map(|r| r.club.as_str()).unwrap_or("?");
    if json {
        let out: Vec<_> = points
            .iter()
            .map(|p| {
                serde_json::json!({
                    "apex_tolerance_yd": p.apex_tolerance_yd,
                    "land_tolerance_deg": p.land_tolerance_deg,
                    "max_land_angle_error_deg": p.max_land_angle_error_deg,
                    "max_carry_error_pct": p.max_carry_error_pct,
                    "max_apex_error_yd": p.max_apex_error_yd,
                    "worst_carry_club": club(p.worst_carry_club),
                    "worst_land_club": club(p.worst_land_club),
                    "aero": p.aero,
                })
            })
            .collect();
        let current = tradeoff::largest_errors(&impactd::flight::Aero::FITTED, rows);
        let doc = serde_json::json!({
            "carry_tolerance_pct": tradeoff::CARRY_PCT,
            "points": out,
            "fitted": {
                "max_land_angle_error_deg": current.0,
                "max_carry_error_pct": current.1,
                "max_apex_error_yd": current.2,
                "worst_carry_club": club(current.3),
                "worst_land_club": club(current.4),
            },
        });
        println!("{}", serde_json::to_string_pretty(&doc)?);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{:>12} {:>14} {:>16} {:>16} {:>14}",
        "apex scale yd", "land scale deg", "land max deg", "carry max %", "apex max yd"
    );
    for p in &points {
        println!(
            "{:>12} {:>14.1} {:>10.2} ({:<6}) {:>10.2} ({:<6}) {:>14.2}",
            p.apex_tolerance_yd.map_or("free".to_string(), |a| format!("{a:.0}")),
            p.land_tolerance_deg,
            p.max_land_angle_error_deg,
            club(p.worst_land_club),
            p.max_carry_error_pct,
            club(p.worst_carry_club),
            p.max_apex_error_yd
        );
    }
    Ok(ExitCode::SUCCESS)
}
