//! `impactd flight-fit`: refits the flight model's coefficients to the TrackMan tour averages and shows the fit.

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Args;

#[derive(Debug, Args)]
pub struct FlightFitArgs {
    /// Nelder-Mead iterations per restart, from `flight::fit::START`, before the minimax stage (0: show the
    /// errors of `Aero::FITTED`).
    #[arg(long, default_value_t = 3000)]
    pub iterations: usize,
}

pub fn run(args: &FlightFitArgs) -> Result<ExitCode> {
    let iterations = args.iterations;
    use impactd::flight::fit;
    let rows = fit::parse_table(fit::TRACKMAN_CSV).context("TrackMan table")?;
    let current = impactd::flight::Aero::FITTED;
    let (aero, cost, worst) = if iterations == 0 {
        (current, fit::cost(&current, &rows), fit::worst(&current, &rows))
    } else {
        eprintln!("fitting from fit::START ({iterations} Nelder-Mead iterations per restart, then minimax)...");
        let f = fit::fit(&rows, &fit::START, iterations, |step| match step {
            fit::Step::Run(run, cost) => eprintln!("Nelder-Mead run {run}: cost {cost:.4}"),
            fit::Step::Minimax(i, worst) => eprintln!("minimax {i}: largest scaled error {worst:.6}"),
        });
        (f.aero, f.cost, f.worst)
    };
    println!(
        "{} (largest error {:.4} of its target, cost {cost:.4}): {aero:?}",
        if iterations == 0 { "current" } else { "fitted" },
        worst
    );
    println!("{:<8} {:>15} {:>13} {:>14}  within", "club", "carry yd", "apex yd", "land deg");
    let mut within = 0;
    for r in &rows {
        let (c, a, l) = fit::predict(&aero, r);
        let (dc, da, dl) = (c - r.carry_yd, a - r.max_height_yd, l - r.land_angle_deg);
        let ok = dc.abs() <= 3.0 && da.abs() <= 2.0 && dl.abs() <= 2.0;
        within += usize::from(ok);
        println!(
            "{:<8} {:>6.1} ({:+6.2}) {:>5.1} ({:+5.2}) {:>5.1} ({:+5.2})  {}",
            r.club,
            c,
            dc,
            a,
            da,
            l,
            dl,
            if ok { "yes" } else { "no" }
        );
    }
    println!("{within} of {} clubs within carry 3 yd, apex 2 yd and land angle 2 deg", rows.len());
    Ok(ExitCode::SUCCESS)
}
