//! Fig. 13: pull-off force against the modified Johnson parameter alpha* (Eq. 15) for Tabor
//! parameters 2, 5 and 7.

use crate::rough_sphere::{
    Drawn, MODULUS, PullOffFigure, Spec, Z0, largest_spread, plan, points, work_of_adhesion,
};
use crate::{Context, FigureReport};
use anyhow::Result;
use std::f64::consts::PI;

/// The rough points of Figs. 13-14 (Fig. 11's roughnesses, mu = 2, 5, 7).
pub fn wanted(ctx: &Context) -> Vec<Spec> {
    let p = plan(ctx);
    p.mus_run(13)
        .into_iter()
        .flat_map(|mu| {
            p.rqs
                .iter()
                .filter(|&&rq| rq > 0.0)
                .map(move |&rq| Spec::new(mu, rq))
        })
        .collect()
}

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let pts = points(ctx, &wanted(ctx))?;
    let fig = PullOffFigure {
        number: 13,
        title: "Pull-off force vs the modified Johnson parameter α*",
        x_label: "modified Johnson parameter α* (Eq. 15)",
        x_name: "johnson_parameter",
        x_log: true,
        legend: crate::plot::Legend::LowerRight,
        legend_room: false,
        collapse: true,
    };
    let johnson = |pt: &crate::rough_sphere::Point| {
        let o = &pt.outcomes[0];
        theory::rough::johnson_parameter(
            work_of_adhesion(pt.spec.mu),
            MODULUS,
            pt.mean(|o| o.rq),
            2.0 * PI / o.length,
            2.0 * PI / o.cutoff,
            pt.spec.hurst,
        )
    };
    let Drawn {
        mut report,
        curves,
        other_spread,
    } = fig.draw(ctx, &pts, johnson, Vec::new())?;
    report.computed.push(format!(
        "α* = (4 w0 q1^(0.8H-1) / (π E* Rq² q0^(0.8H)))² with q0 = 2π/L (the box), q1 the short cutoff, H = 0.8, \
         Rq measured; roughness {:?} z0 (z0 = {} nm).",
        plan(ctx).rqs.iter().filter(|&&r| r > 0.0).collect::<Vec<_>>(),
        Z0 * 1e9
    ));
    let rising = |c: &[(f64, f64)]| c.windows(2).all(|w| w[1].1 >= w[0].1 - 0.02);
    for (mu, c) in &curves {
        report.agreement.push(format!(
            "μ = {mu}: α* from {:.3e} to {:.3e}, pull-off from {:.3} to {:.3} πRw0; rising with α* (larger α* \
             stickier, as Li, Pohrt & Popov predict): {}.",
            c[0].0,
            c[c.len() - 1].0,
            c[0].1,
            c[c.len() - 1].1,
            if rising(c) { "yes" } else { "no (see the table)" }
        ));
    }
    let all_rise = curves.iter().all(|(_, c)| rising(c));
    report.claim = "The pull-off force rises with the modified Johnson parameter α*, and the curves of the \
                    Tabor parameters are \"very similar\"."
        .into();
    let spread = (curves.len() > 1)
        .then(|| largest_spread(&curves.iter().map(|(_, c)| c.clone()).collect::<Vec<_>>()))
        .flatten();
    if let Some(s) = spread {
        report.agreement.push(format!(
            "Spread between the Tabor parameters' mean pull-offs ({}): {:.0} % at equal α*.",
            crate::rough_sphere::SPREAD,
            100.0 * s
        ));
    }
    report.verdict = format!(
        "{}{}",
        if all_rise {
            "Reproduced for the trend: the pull-off rises with α* at every Tabor parameter"
        } else {
            "Not reproduced: the pull-off does not rise with α* at every Tabor parameter"
        },
        match spread {
            Some(s) => format!(
                "; the curves spread by {:.0} % at equal α*{} (the paper: \"very similar\").",
                100.0 * s,
                crate::rough_sphere::other_words(ctx, other_spread)
            ),
            None => ".".into(),
        }
    );
    Ok(report)
}
