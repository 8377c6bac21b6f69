//! Fig. 12: pull-off force against the RMS gradient at a fixed RMS roughness (Rq = 2 z0),
//! Tabor parameters 5 and 7. The gradient is varied through the Hurst exponent, the roll-off
//! (half the box) and the cutoff held: at fixed Rq a lower H moves the roughness
//! towards short wavelengths and raises the gradient, while the largest wavelength, which
//! Ciavarella's criterion (Fig. 14) turns on, stays. Moving the cutoff instead barely moves
//! the gradient (H = 0.8: 0.0042 to 0.0061 over cutoffs of 205 to 51 nm); moving the roll-off
//! moves the largest wavelength with it.

use crate::rough_sphere::{Drawn, Point, PullOffFigure, Spec, curve_of, falling, plan, points};
use crate::{Context, FigureReport};
use anyhow::Result;

/// The figure's points: each Tabor parameter at each Hurst exponent, Rq = 2 z0.
pub fn wanted(ctx: &Context) -> Vec<Spec> {
    let p = plan(ctx);
    p.mus_run(12)
        .into_iter()
        .flat_map(|mu| {
            p.hursts.iter().map(move |&hurst| Spec {
                hurst,
                ..Spec::new(mu, 2.0)
            })
        })
        .collect()
}

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let p = plan(ctx);
    let pts = points(ctx, &wanted(ctx))?;
    let fig = PullOffFigure {
        number: 12,
        title: "Pull-off force of rough spheres vs RMS gradient (Rq = 2 z0)",
        x_label: "RMS gradient ḡ",
        x_name: "rms_gradient",
        x_log: false,
        legend: crate::plot::Legend::UpperRight,
        legend_room: true,
        collapse: false,
    };
    let Drawn {
        mut report, curves, ..
    } = fig.draw(ctx, &pts, |pt| pt.mean(|o| o.rms_gradient), Vec::new())?;
    let all_fall = curves.iter().all(|(_, c)| falling(c, 0.02));
    let changes: Vec<(u32, Change)> = curves.iter().map(|(mu, _)| (*mu, change(&pts, *mu))).collect();
    report.claim =
        "At a fixed RMS roughness (Rq = 2 z0) the pull-off force falls as the RMS gradient grows.".into();
    report.verdict = if all_fall {
        "Reproduced: the mean pull-off falls with ḡ at every Tabor parameter.".into()
    } else {
        format!(
            "Not reproduced: at fixed Rq and largest wavelength the pull-off {} from the smallest ḡ to the largest \
             ({}; ḡ varied through the Hurst exponent). Ciavarella's variable Rq² E*/(λL w0), which orders the \
             pull-offs of Fig. 14, is the same at every point of this figure.",
            if changes.iter().all(|(_, c)| c.mean > 2.0 * c.error) {
                "rises"
            } else {
                "does not fall"
            },
            changes
                .iter()
                .map(|(mu, c)| format!(
                    "μ = {mu}: {:+.3} ± {:.3} πRw0, paired over the seeds",
                    c.mean, c.error
                ))
                .collect::<Vec<_>>()
                .join("; ")
        )
    };
    report.computed.push(format!(
        "ḡ varied through the Hurst exponent H = {:?} at fixed Rq, roll-off (half the box) and cutoff: \
         the largest wavelength stays; what changes with ḡ besides is the spectrum's shape (a lower H puts more \
         of Rq in short wavelengths).",
        p.hursts
    ));
    for ((mu, c), (_, ch)) in curves.iter().zip(&changes) {
        report.agreement.push(format!(
            "μ = {mu}: pull-off {:.3} πRw0 at ḡ = {:.4}, {:.3} at ḡ = {:.4} ({:+.0} %); the change seed by seed \
             (each seed's phases are shared by its Hurst exponents) {:+.3} ± {:.3} πRw0 (mean ± standard error), \
             up in {} of {}; means {}; falling with ḡ at every step: {}.",
            c[0].1,
            c[0].0,
            c[c.len() - 1].1,
            c[c.len() - 1].0,
            100.0 * (c[c.len() - 1].1 / c[0].1 - 1.0),
            ch.mean,
            ch.error,
            ch.up,
            ch.seeds,
            c.iter().map(|(_, f)| format!("{f:.3}")).collect::<Vec<_>>().join(", "),
            if falling(c, 0.02) { "yes" } else { "no (see the table)" }
        ));
    }
    // The same seed at every Hurst exponent shares its random phases: the trend of each realisation
    // is free of part of the scatter between realisations.
    for (mu, _) in &curves {
        for (k, seed) in p.seeds.iter().enumerate() {
            let c = curve_of(&pts, *mu, |pt| {
                let o = &pt.outcomes[k];
                (o.rms_gradient, o.pull_off / pt.job.force_unit())
            });
            report.agreement.push(format!(
                "μ = {mu}, seed {seed} alone: pull-off {} from the smallest ḡ to the largest; falling with ḡ: {}.",
                c.iter().map(|(_, f)| format!("{f:.3}")).collect::<Vec<_>>().join(", "),
                if falling(&c, 0.0) { "yes" } else { "no" }
            ));
        }
    }
    Ok(report)
}

/// The change of the pull-off [pi R w0] from the smallest to the largest ḡ of one Tabor
/// parameter, seed by seed: a seed's realisations share their random phases across the Hurst
/// exponents, so the paired change is free of the scatter between realisations.
struct Change {
    mean: f64,
    /// The standard error of `mean`.
    error: f64,
    /// Seeds whose pull-off rose, and all seeds.
    up: usize,
    seeds: usize,
}

fn change(points: &[Point], mu: u32) -> Change {
    let mut of_mu: Vec<&Point> = points.iter().filter(|p| p.spec.mu == mu).collect();
    of_mu.sort_by(|a, b| a.mean(|o| o.rms_gradient).total_cmp(&b.mean(|o| o.rms_gradient)));
    let (first, last) = (of_mu[0], of_mu[of_mu.len() - 1]);
    let d: Vec<f64> = first
        .outcomes
        .iter()
        .zip(&last.outcomes)
        .map(|(a, b)| (b.pull_off - a.pull_off) / first.job.force_unit())
        .collect();
    let (mean, std) = crate::rough_sphere::mean_std(&d);
    Change {
        mean,
        error: std / (d.len() as f64).sqrt(),
        up: d.iter().filter(|&&x| x > 0.0).count(),
        seeds: d.len(),
    }
}
