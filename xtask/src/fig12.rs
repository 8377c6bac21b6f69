//! Fig. 12: pull-off force against the RMS gradient at a fixed RMS roughness (Rq = 2 z0),
//! Tabor parameters 5 and 7; the gradient is varied through the short-wavelength cutoff.

use crate::rough_sphere::{PullOffFigure, curve_of, falling, plan, points};
use crate::{Context, FigureReport};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let p = plan(ctx);
    let wanted: Vec<(u32, f64, f64)> = p
        .mus_run(12)
        .into_iter()
        .flat_map(|mu| p.cutoffs.iter().map(move |&c| (mu, 2.0, c)))
        .collect();
    let pts = points(ctx, "Fig. 12", &wanted)?;
    let fig = PullOffFigure {
        number: 12,
        title: "Pull-off force of rough spheres vs RMS gradient (Rq = 2 z0)",
        x_label: "RMS gradient ḡ",
        x_name: "rms_gradient",
        x_log: false,
        legend: crate::style::Legend::UpperRight,
    };
    let (mut report, curves) = fig.draw(ctx, &pts, |pt| pt.mean(|o| o.rms_gradient), Vec::new())?;
    report.computed.push(format!(
        "ḡ varied through the short cutoff: {:?} cells.",
        p.cutoffs
    ));
    for (mu, c) in &curves {
        report.agreement.push(format!(
            "μ = {mu}: pull-off {:.3} πRw0 at ḡ = {:.4}, {:.3} at ḡ = {:.4}; falling with ḡ: {}.",
            c[0].1,
            c[0].0,
            c[c.len() - 1].1,
            c[c.len() - 1].0,
            if falling(c, 0.02) {
                "yes"
            } else {
                "no (see the table)"
            }
        ));
    }
    // The same seed at every cutoff shares its long wavelengths, which set the pull-off: the
    // trend of each realisation is free of the scatter between realisations.
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
