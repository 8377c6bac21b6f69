//! Fig. 9: the gap along the mid cross-section (x = 50 um) of the challenge contact at
//! p/(E* g_bar) = 0.01, without and with adhesion.

use crate::fig08;
use crate::plot::{Chart, Curve, Mark, PALETTE};
use crate::{Context, FigureReport, Table};
use anyhow::Result;

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let runs = fig08::runs(ctx);
    let out = crate::challenge::outcomes(ctx, &runs)?;
    let rungs = fig08::rungs(ctx, &out);
    // The profile of the finest grid.
    let finest = rungs.last().expect("a grid");
    let (plain, sticky) = (finest.plain, finest.sticky);
    let mut report = FigureReport::new(
        9,
        "Challenge contact: gap along the mid cross-section at p/(E* g_bar) = 0.01",
    );
    report.computed = fig08::computed(ctx, &rungs);
    report
        .computed
        .push(format!("The profile is {}'s.", fig08::grid_name(ctx, finest.n)));
    report.solver_seconds = [plain, sticky]
        .iter()
        .flat_map(|o| &o.points)
        .map(|p| p.wall_time_s)
        .sum();
    let n = plain.profile.len();
    let dy = plain.cell;
    let mut table = Table::new(
        "fig09",
        &[
            "y_um",
            "gap_no_adhesion_nm",
            "gap_adhesion_nm",
            "gap_difference_nm",
        ],
    );
    for j in 0..n {
        let (a, b) = (plain.profile[j] * 1e9, sticky.profile[j] * 1e9);
        table.push(vec![j as f64 * dy * 1e6, a, b, b - a]);
    }
    let mut chart = Chart::new("Gap along x = 50 µm at p/(E* ḡ) = 0.01", "y (µm)", "gap (nm)");
    chart.curves.push(Curve::new(
        "no adhesion",
        table.rows.iter().map(|r| (r[0], r[1])).collect(),
        Mark::Line,
        PALETTE[0],
    ));
    chart.curves.push(Curve::new(
        format!(
            "adhesion ({})",
            crate::challenge::label(ctx.options.challenge_law)
        ),
        table.rows.iter().map(|r| (r[0], r[2])).collect(),
        Mark::Line,
        PALETTE[3],
    ));
    // The two gaps differ by nanometres where they are micrometres: the difference on its own
    // axis.
    let mut difference = Chart::new(
        "Adhesive minus non-adhesive gap along the same line",
        "y (µm)",
        "gap difference (nm)",
    );
    difference.curves.push(Curve::new(
        "adhesion - no adhesion",
        table.rows.iter().map(|r| (r[0], r[3])).collect(),
        Mark::Line,
        PALETTE[3],
    ));
    report.save(&[chart, difference], &ctx.options.out, "fig09")?;
    let closed = |g: &[f64]| g.iter().filter(|&&v| v <= 0.0).count() as f64 / g.len() as f64;
    let mean = |g: &[f64]| g.iter().sum::<f64>() / g.len() as f64;
    report.agreement.push(format!(
        "Along the line: {:.1} % in contact without adhesion, {:.1} % with it; mean gap {:.1} nm and {:.1} nm; \
         adhesion changes the gap by at most {:.1} nm along the line. The paper's GFMD reference profile is not \
         available here.",
        100.0 * closed(&plain.profile),
        100.0 * closed(&sticky.profile),
        mean(&plain.profile) * 1e9,
        mean(&sticky.profile) * 1e9,
        plain
            .profile
            .iter()
            .zip(&sticky.profile)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            * 1e9
    ));
    report.tables.push(table);
    report.claim =
        "The gap along the challenge's mid cross-section (x = 50 µm) at p/(E* ḡ) = 0.01 agrees with \
                    the GFMD reference."
            .into();
    report.verdict = format!(
        "Not tested: the GFMD reference profile is not available here{}; the figure shows the profiles and what \
         adhesion changes.",
        if ctx.options.challenge_surface.is_some() {
            ""
        } else {
            ", and the surface is generated from the specification rather than the challenge's own"
        }
    );
    Ok(report)
}
