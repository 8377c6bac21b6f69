//! Fig. 14: pull-off force against Ciavarella's variable Rq^2 E*/(lambda_L w0) (Eq. 16) for
//! Tabor parameters 2, 5 and 7, with his stickiness threshold.

use crate::plot::{Curve, GREY, Mark};
use crate::rough_sphere::{MODULUS, PullOffFigure, crossing, curve_of, points, work_of_adhesion};
use crate::{Context, FigureReport};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let pts = points(ctx, &crate::fig13::wanted(ctx))?;
    let fig = PullOffFigure {
        number: 14,
        title: "Pull-off force vs Ciavarella's variable Rq² E*/(λL w0)",
        x_label: "Rq² E* / (λL w0)",
        x_name: "ciavarella_variable",
        x_log: true,
        legend: crate::plot::Legend::UpperRight,
        roughness_column: ("cutoff_cells", |s| s.cutoff_cells),
    };
    let x = |pt: &crate::rough_sphere::Point| {
        theory::rough::ciavarella_variable(
            pt.mean(|o| o.rq),
            MODULUS,
            pt.outcomes[0].length,
            work_of_adhesion(pt.spec.mu),
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
    // A measure that needs no common level: how far apart the Tabor parameters' pull-offs
    // are at equal abscissa, over the range all of them cover.
    if curves.len() > 1 {
        let against_x: Vec<Vec<(f64, f64)>> = curves.iter().map(|(_, c)| c.clone()).collect();
        let against_rq: Vec<Vec<(f64, f64)>> = curves
            .iter()
            .map(|(mu, _)| curve_of(&pts, *mu, |p| (p.mean(|o| o.rq), p.pull_off().0)))
            .collect();
        let show = |s: Option<f64>| s.map_or("no common range".into(), |s| format!("{:.0} %", 100.0 * s));
        report.agreement.push(format!(
            "Spread between the Tabor parameters' mean pull-offs (largest (max - min) / mean over the range \
             of the abscissa they share, 16 points evenly in its logarithm): {} at equal Ciavarella variable, \
             {} at equal Rq.",
            show(largest_spread(&against_x)),
            show(largest_spread(&against_rq))
        ));
    }
    Ok(report)
}

/// `curve`'s value at `x`, linear in `ln x` between its points (sorted by x, x > 0); `None`
/// outside them.
fn at_log(curve: &[(f64, f64)], x: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        (x0 > 0.0 && x0 <= x && x <= x1).then(|| {
            let t = if x1 > x0 {
                (x / x0).ln() / (x1 / x0).ln()
            } else {
                0.0
            };
            y0 + t * (y1 - y0)
        })
    })
}

/// The largest `(max - min) / mean` of the curves' values over the x range they all cover,
/// sampled at 16 points evenly in `ln x`; `None` when they share no range.
fn largest_spread(curves: &[Vec<(f64, f64)>]) -> Option<f64> {
    let positive = |c: &Vec<(f64, f64)>| c.iter().map(|p| p.0).filter(|&x| x > 0.0).collect::<Vec<_>>();
    let lo = curves
        .iter()
        .map(|c| positive(c).into_iter().fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max);
    let hi = curves
        .iter()
        .map(|c| positive(c).into_iter().fold(0.0, f64::max))
        .fold(f64::INFINITY, f64::min);
    if !(lo > 0.0 && hi > lo) {
        return None;
    }
    (0..16)
        .map(|k| {
            let x = lo * (hi / lo).powf(k as f64 / 15.0);
            let ys: Vec<f64> = curves.iter().filter_map(|c| at_log(c, x)).collect();
            let mean = ys.iter().sum::<f64>() / ys.len() as f64;
            let (min, max) = ys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
                (a.min(y), b.max(y))
            });
            (max - min) / mean
        })
        .reduce(f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_at_equal_abscissa() {
        let a = vec![(1.0, 2.0), (4.0, 1.0)];
        // Linear in ln x: halfway in the logarithm at x = 2.
        assert!((at_log(&a, 2.0).unwrap() - 1.5).abs() < 1e-12);
        assert_eq!(at_log(&a, 8.0), None);
        // Identical curves do not spread; a curve twice as high spreads by 2/3 of the mean.
        assert_eq!(largest_spread(&[a.clone(), a.clone()]), Some(0.0));
        let b: Vec<(f64, f64)> = a.iter().map(|&(x, y)| (x, 2.0 * y)).collect();
        assert!((largest_spread(&[a.clone(), b]).unwrap() - 2.0 / 3.0).abs() < 1e-12);
        // Disjoint ranges share nothing.
        assert_eq!(largest_spread(&[a, vec![(5.0, 1.0), (6.0, 1.0)]]), None);
    }
}
