//! The optimisers of the identification, in the unit cube `[0, 1]^d`: differential evolution for the global
//! search (Storn and Price 1997, the `rand-to-best/1/bin` strategy with a dithered weight) and Nelder-Mead for
//! the local refinement (Nelder and Mead 1965; Gao and Han's dimension-adapted coefficients). The seed used a
//! genetic algorithm (population 200, 100 generations) and then `fmincon` (section 3.1.3); eq. 3.13 is a sum of
//! absolute values, not smooth, which suits a derivative-free refinement.
//!
//! Both are deterministic for a seed: random numbers come from [`crate::rng::Rng`] in a fixed order, and the
//! objective is evaluated one point at a time (each evaluation is itself parallel over shots).

use crate::math::Real;
use crate::rng::Rng;

/// Where the search is, for progress reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// `"global"` or `"local"`.
    pub stage: &'static str,
    /// Generation (global) or iteration (local), and the planned total.
    pub step: usize,
    pub steps: usize,
    pub evaluations: usize,
    pub best_cost: Real,
}

/// Settings of the differential evolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeOptions {
    pub population: usize,
    pub generations: usize,
    /// Crossover probability.
    pub crossover: Real,
    /// The difference weight is drawn per generation from this range (dither).
    pub weight: (Real, Real),
    /// Stop when the population's costs span less than this (relative to the best).
    pub tolerance: Real,
    /// Stop when the best cost has improved by less than `stall_tolerance` (relative) over this many
    /// generations (0: never): the basin is found, and the local refinement does the rest more cheaply.
    pub stall_generations: usize,
    pub stall_tolerance: Real,
    pub seed: u64,
}

impl DeOptions {
    /// Ten members per parameter (at least 20), 100 generations.
    pub fn for_dimension(d: usize, seed: u64) -> Self {
        DeOptions {
            population: (10 * d).max(20),
            generations: 100,
            crossover: 0.9,
            weight: (0.5, 0.9),
            tolerance: 1e-6,
            stall_generations: 0,
            stall_tolerance: 1e-3,
            seed,
        }
    }
}

/// A point and its cost.
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    pub x: Vec<Real>,
    pub cost: Real,
    pub evaluations: usize,
}

/// Differential evolution over `[0, 1]^d`. `start`, when given, is one member of the first population.
pub fn differential_evolution(
    f: &mut dyn FnMut(&[Real]) -> Real,
    d: usize,
    start: Option<&[Real]>,
    options: &DeOptions,
    progress: &mut dyn FnMut(Progress),
) -> Minimum {
    let mut rng = Rng::new(options.seed);
    let np = options.population.max(4);
    // Stratified first population: each coordinate takes every one of np strata once (Latin hypercube).
    let mut pop: Vec<Vec<Real>> = vec![vec![0.0; d]; np];
    for k in 0..d {
        let mut strata: Vec<usize> = (0..np).collect();
        for i in (1..np).rev() {
            strata.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
        }
        for (member, s) in pop.iter_mut().zip(strata) {
            member[k] = (s as Real + rng.unit()) / np as Real;
        }
    }
    if let Some(s) = start {
        pop[0] = s.iter().map(|v| v.clamp(0.0, 1.0)).collect();
    }
    let mut costs: Vec<Real> = pop.iter().map(|x| f(x)).collect();
    let mut evaluations = np;
    let best_of = |costs: &[Real]| (0..costs.len()).fold(0, |b, i| if costs[i] < costs[b] { i } else { b });
    let mut history = vec![costs[best_of(&costs)]];
    for generation in 0..options.generations {
        let best = best_of(&costs);
        let weight = rng.uniform(options.weight.0, options.weight.1);
        for i in 0..np {
            let mut pick = |exclude: &[usize]| loop {
                let r = (rng.next_u64() % np as u64) as usize;
                if !exclude.contains(&r) {
                    break r;
                }
            };
            let r1 = pick(&[i]);
            let r2 = pick(&[i, r1]);
            let r3 = pick(&[i, r1, r2]);
            let forced = (rng.next_u64() % d.max(1) as u64) as usize;
            let mut trial = pop[i].clone();
            for k in 0..d {
                if k == forced || rng.unit() < options.crossover {
                    let v = pop[r1][k] + weight * (pop[best][k] - pop[r1][k]) + weight * (pop[r2][k] - pop[r3][k]);
                    // Bounce back inside: halfway between the parent and the bound it crossed.
                    trial[k] = if v < 0.0 {
                        0.5 * pop[i][k]
                    } else if v > 1.0 {
                        0.5 * (1.0 + pop[i][k])
                    } else {
                        v
                    };
                }
            }
            let c = f(&trial);
            evaluations += 1;
            if c <= costs[i] {
                pop[i] = trial;
                costs[i] = c;
            }
        }
        let best = best_of(&costs);
        progress(Progress {
            stage: "global",
            step: generation + 1,
            steps: options.generations,
            evaluations,
            best_cost: costs[best],
        });
        let worst = costs.iter().copied().fold(Real::NEG_INFINITY, Real::max);
        if worst - costs[best] <= options.tolerance * costs[best].abs().max(1e-12) {
            break;
        }
        history.push(costs[best]);
        let k = options.stall_generations;
        if k > 0 && history.len() > k {
            let gain = history[history.len() - 1 - k] - costs[best];
            if gain <= options.stall_tolerance * costs[best].abs().max(1e-12) {
                break;
            }
        }
    }
    let best = best_of(&costs);
    Minimum { x: pop[best].clone(), cost: costs[best], evaluations }
}

/// Settings of the Nelder-Mead refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NmOptions {
    /// Initial simplex edge (unit-cube coordinates).
    pub step: Real,
    pub max_evaluations: usize,
    /// Stop when the simplex's costs span less than this and its size is below `x_tolerance`.
    pub f_tolerance: Real,
    pub x_tolerance: Real,
}

impl Default for NmOptions {
    fn default() -> Self {
        NmOptions { step: 0.02, max_evaluations: 400, f_tolerance: 1e-9, x_tolerance: 1e-6 }
    }
}

/// Nelder-Mead from `x0` in `[0, 1]^d` (points are clamped into the cube).
pub fn nelder_mead(
    f: &mut dyn FnMut(&[Real]) -> Real,
    x0: &[Real],
    options: &NmOptions,
    progress: &mut dyn FnMut(Progress),
) -> Minimum {
    let d = x0.len();
    let n = d as Real;
    // Gao and Han (2012): coefficients adapted to the dimension.
    let (alpha, gamma, rho, sigma) = (1.0, 1.0 + 2.0 / n, 0.75 - 0.5 / n, 1.0 - 1.0 / n);
    let clamp = |x: Vec<Real>| x.into_iter().map(|v| v.clamp(0.0, 1.0)).collect::<Vec<_>>();
    let mut simplex: Vec<Vec<Real>> = vec![clamp(x0.to_vec())];
    for k in 0..d {
        let mut x = simplex[0].clone();
        x[k] = if x[k] + options.step <= 1.0 { x[k] + options.step } else { x[k] - options.step };
        simplex.push(x);
    }
    let mut costs: Vec<Real> = simplex.iter().map(|x| f(x)).collect();
    let mut evaluations = d + 1;
    let planned = options.max_evaluations;
    while evaluations < options.max_evaluations {
        let mut order: Vec<usize> = (0..=d).collect();
        order.sort_by(|&a, &b| costs[a].total_cmp(&costs[b]));
        simplex = order.iter().map(|&i| simplex[i].clone()).collect();
        costs = order.iter().map(|&i| costs[i]).collect();
        progress(Progress { stage: "local", step: evaluations, steps: planned, evaluations, best_cost: costs[0] });
        let size = simplex[1..]
            .iter()
            .map(|x| x.iter().zip(&simplex[0]).map(|(a, b)| (a - b).abs()).fold(0.0, Real::max))
            .fold(0.0, Real::max);
        if costs[d] - costs[0] <= options.f_tolerance * costs[0].abs().max(1e-12) && size <= options.x_tolerance {
            break;
        }
        let centroid: Vec<Real> = (0..d).map(|k| simplex[..d].iter().map(|x| x[k]).sum::<Real>() / n).collect();
        let along = |t: Real| clamp((0..d).map(|k| centroid[k] + t * (simplex[d][k] - centroid[k])).collect());
        let reflected = along(-alpha);
        let fr = f(&reflected);
        evaluations += 1;
        if fr < costs[0] {
            let expanded = along(-alpha * gamma);
            let fe = f(&expanded);
            evaluations += 1;
            if fe < fr {
                simplex[d] = expanded;
                costs[d] = fe;
            } else {
                simplex[d] = reflected;
                costs[d] = fr;
            }
        } else if fr < costs[d - 1] {
            simplex[d] = reflected;
            costs[d] = fr;
        } else {
            let (contracted, fc) = if fr < costs[d] {
                let c = along(-alpha * rho);
                let fc = f(&c);
                (c, fc)
            } else {
                let c = along(rho);
                let fc = f(&c);
                (c, fc)
            };
            evaluations += 1;
            if fc < fr.min(costs[d]) {
                simplex[d] = contracted;
                costs[d] = fc;
            } else {
                // Shrink toward the best.
                for i in 1..=d {
                    simplex[i] = (0..d).map(|k| simplex[0][k] + sigma * (simplex[i][k] - simplex[0][k])).collect();
                    costs[i] = f(&simplex[i]);
                }
                evaluations += d;
            }
        }
    }
    let best = (0..=d).fold(0, |b, i| if costs[i] < costs[b] { i } else { b });
    Minimum { x: simplex[best].clone(), cost: costs[best], evaluations }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's valley moved into the cube: minimum 0 at (0.6, 0.5).
    fn rosenbrock(x: &[Real]) -> Real {
        let (a, b) = (5.0 * x[0] - 2.0, 5.0 * x[1] - 1.5);
        (1.0 - a).powi(2) + 100.0 * (b - a * a).powi(2)
    }

    #[test]
    fn de_then_nelder_mead_find_rosenbrocks_minimum_and_repeat_for_a_seed() {
        let run = |seed| {
            let mut f = |x: &[Real]| rosenbrock(x);
            let g = differential_evolution(&mut f, 2, None, &DeOptions::for_dimension(2, seed), &mut |_| {});
            nelder_mead(&mut f, &g.x, &NmOptions { max_evaluations: 2000, ..Default::default() }, &mut |_| {})
        };
        let m = run(3);
        // The closed-form minimum: a = b = 1, i.e. x = (0.6, 0.5).
        assert!((m.x[0] - 0.6).abs() < 1e-4 && (m.x[1] - 0.5).abs() < 1e-4, "{m:?}");
        assert!(m.cost < 1e-8);
        assert_eq!(run(3), m);
    }

    #[test]
    fn a_stalled_search_stops_early() {
        // A flat cost never improves: with a stall window of 5 generations the search stops after 5.
        let mut f = |_: &[Real]| 1.0;
        let mut options = DeOptions::for_dimension(2, 1);
        options.tolerance = -1.0;
        options.stall_generations = 5;
        let m = differential_evolution(&mut f, 2, None, &options, &mut |_| {});
        assert_eq!(m.evaluations, options.population * (1 + 5));
    }

    #[test]
    fn nelder_mead_on_an_absolute_value_sum() {
        // |x - 0.3| + 2 |y - 0.7|: the kind of non-smooth sum eq. 3.13 is.
        let mut f = |x: &[Real]| (x[0] - 0.3).abs() + 2.0 * (x[1] - 0.7).abs();
        let m = nelder_mead(&mut f, &[0.5, 0.5], &NmOptions::default(), &mut |_| {});
        assert!((m.x[0] - 0.3).abs() < 1e-5 && (m.x[1] - 0.7).abs() < 1e-5, "{m:?}");
    }
}
