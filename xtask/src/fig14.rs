//! Fig. 14: pull-off force against Ciavarella's variable Rq^2 E*/(lambda_L w0) (Eq. 16) for
//! Tabor parameters 2, 5 and 7, with his stickiness threshold.

use crate::rough_sphere::{MODULUS, PullOffFigure, crossing, curve_of, points, work_of_adhesion};
use crate::style::{Curve, GREY, Mark};
use crate::{Context, FigureReport};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let pts = points(ctx, "Fig. 14", &crate::fig13::wanted(ctx))?;
    let fig = PullOffFigure {
        number: 14,
        title: "Pull-off force vs Ciavarella's variable Rq² E*/(λL w0)",
        x_label: "Rq² E* / (λL w0)",
        x_name: "ciavarella_variable",
        x_log: true,
        legend: crate::style::Legend::UpperRight,
    };
    let x = |pt: &crate::rough_sphere::Point| {
        theory::rough::ciavarella_variable(
            pt.mean(|o| o.rq),
            MODULUS,
            pt.outcomes[0].length,
            work_of_adhesion(pt.mu),
        )
    };
    let hi = pts.iter().map(|p| p.pull_off().0).fold(0.0, f64::max);
    let threshold = Curve::new(
        "Ciavarella: sticky below 0.6",
        vec![(0.6, 0.0), (0.6, hi * 1.05)],
        Mark::Dashed,
        GREY,
    );
    let (mut report, curves) = fig.draw(ctx, &pts, x, vec![threshold])?;
    report.computed.push(
        "λL is the longest wavelength of the roughness: the box side (the spectrum is flat from 2π/L to the \
         roll-off)."
            .into(),
    );
    // Collapse: where each mu's pull-off falls to half of the JKR value 1.5 pi R w0.
    let half: Vec<String> = curves
        .iter()
        .map(|(mu, c)| match crossing(c, 0.75) {
            Some(x) => format!("μ = {mu}: {x:.3}"),
            None => format!("μ = {mu}: not reached"),
        })
        .collect();
    // The same crossing against Rq alone: how far apart the Tabor parameters are before
    // Ciavarella's scaling.
    let in_rq: Vec<String> = curves
        .iter()
        .map(|(mu, _)| {
            let c = curve_of(&pts, *mu, |p| (p.mean(|o| o.rq) * 1e9, p.pull_off().0));
            match crossing(&c, 0.75) {
                Some(x) => format!("μ = {mu}: {x:.2} nm"),
                None => format!("μ = {mu}: not reached"),
            }
        })
        .collect();
    report.agreement.push(format!(
        "Collapse: the variable at which the pull-off falls to 0.75 πRw0 (half of JKR's) is {} (against Rq \
         alone: {}) — the closer these are, the better Ciavarella's variable collapses the Tabor parameters.",
        half.join(", "),
        in_rq.join(", ")
    ));
    Ok(report)
}
