//! Fig. 10: relative contact area against mean pressure for adhesive rough contact at Tabor
//! parameter 3, for two RMS gradients, against the non-adhesive theory of Müser (Eq. 14).

use crate::challenge::{self, Run};
use crate::plot::{Chart, Curve, Mark, PALETTE};
use crate::{Context, FigureReport, Table};
use anyhow::Result;
use theory::rough::muser_area;

const MU: f64 = 3.0;
/// The RMS gradients compared.
const GRADIENTS: [f64; 2] = [1.0, 0.5];

/// The grid (cells per side).
fn grid(ctx: &Context) -> usize {
    ctx.pick(256, 512)
}

/// Each RMS gradient's work of adhesion [J/m^2] and local radius \[m\].
pub type Works = Vec<(f64, f64)>;

/// The figure's runs, without and with adhesion at each RMS gradient, and the gradients'
/// [`Works`].
pub fn runs(ctx: &Context) -> Result<(Vec<Run>, Works)> {
    let n = grid(ctx);
    let reduced: Vec<f64> = ctx.pick(
        vec![0.0025, 0.005, 0.01, 0.02, 0.04],
        vec![0.00125, 0.0025, 0.005, 0.01, 0.02, 0.04, 0.08],
    );
    let mut runs = Vec::new();
    let mut works = Vec::new();
    for g in GRADIENTS {
        let base = challenge::case(n, g, ctx.options.challenge_surface.as_ref().filter(|_| g == 1.0));
        let (_, radius, _, _) = crate::surface_statistics(&base)?;
        let w0 = challenge::work_for_tabor(radius, MU);
        works.push((w0, radius));
        for case in [
            base.clone(),
            challenge::adhesive(base, w0, ctx.options.challenge_law),
        ] {
            runs.push(Run {
                case,
                reduced: reduced.clone(),
                unloading: Vec::new(),
                profile_at: None,
            });
        }
    }
    Ok((runs, works))
}

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let (n, gradients) = (grid(ctx), GRADIENTS);
    let (runs, works) = runs(ctx)?;
    let reduced = runs[0].reduced.clone();
    let out = challenge::outcomes(ctx, &runs)?;
    let mut report = FigureReport::new(
        10,
        "Adhesive rough contact (μ = 3): relative contact area vs mean pressure",
    );
    let mut table = Table::new(
        "fig10",
        &[
            "rms_gradient",
            "mean_pressure_pa",
            "area_fraction_no_adhesion",
            "area_fraction_adhesion",
            "area_fraction_muser_k2",
            "converged",
        ],
    );
    let mut chart = Chart::new(
        "Adhesive rough contact, Tabor parameter 3",
        "mean pressure p (kPa)",
        "relative contact area a_r",
    );
    chart.x_log = true;
    chart.y_log = true;
    for (i, &g) in gradients.iter().enumerate() {
        let (plain, sticky) = (&out[2 * i], &out[2 * i + 1]);
        let e_g = challenge::MODULUS * plain.rms_gradient;
        for (a, b) in plain.points.iter().zip(&sticky.points) {
            table.push(vec![
                g,
                b.mean_pressure,
                a.contact_area_fraction,
                b.contact_area_fraction,
                muser_area(a.reduced, 2.0),
                b.converged as u8 as f64,
            ]);
            report.solver_seconds += a.wall_time_s + b.wall_time_s;
        }
        draw(&mut chart, (g, i * 3), (plain, sticky), &reduced, e_g);
        let (w0, radius) = works[i];
        report.computed.push(format!(
            "ḡ = {g}: local radius {:.2} µm, w0 = {:.4} J/m² for μ = {:.2}; cells {:.0} process zones wide.",
            radius * 1e6,
            w0,
            challenge::tabor(radius, w0),
            plain.cell / challenge::process_zone(w0, ctx.options.challenge_law)
        ));
        let ratio: Vec<String> = sticky
            .points
            .iter()
            .map(|p| format!("{:.2}", p.contact_area_fraction / muser_area(p.reduced, 2.0)))
            .collect();
        report.agreement.push(format!(
            "ḡ = {g}: adhesive area over Müser's non-adhesive area {} from the lightest load to the heaviest; \
             {} of {} adhesive loads converged.",
            ratio.join(", "),
            sticky.points.iter().filter(|p| p.converged).count(),
            sticky.points.len()
        ));
    }
    // At the lightest load, per RMS gradient: adhesive area over Müser's and over our own
    // non-adhesive run's.
    let gains: Vec<(f64, f64)> = (0..gradients.len())
        .map(|i| {
            let (plain, sticky) = (&out[2 * i].points[0], &out[2 * i + 1].points[0]);
            (
                sticky.contact_area_fraction / muser_area(sticky.reduced, 2.0),
                sticky.contact_area_fraction / plain.contact_area_fraction,
            )
        })
        .collect();
    let factor = gains.iter().map(|g| g.1).fold(0.0, f64::max);
    report.claim =
        "At μ = 3 adhesion raises the relative contact area above the non-adhesive theory (Eq. 14) by \
                    a factor of 2 to 3 at small pressures, less as the pressure grows."
            .into();
    report.verdict = format!(
        "{}: the largest gain at the lightest load is {factor:.2} over our non-adhesive run.",
        if factor >= 2.0 {
            "Reproduced"
        } else {
            "Not reproduced"
        }
    );
    report.agreement.push(gain_note(ctx, &gains, &works, &out));
    report.computed.insert(
        0,
        format!(
            "The challenge's surface specification on {n}² cells (short cutoff {:.2} µm), scaled to RMS gradient \
             1 and 0.5; E* = 25 MPa; adhesion by {}, its w0 chosen per surface so that the Tabor parameter \
             (R w0²/(E*² z0³))^(1/3) with R the inverse RMS curvature is 3. Load control, increasing loads.",
            challenge::cutoff(n) * 1e6,
            challenge::describe(ctx.options.challenge_law)
        ),
    );
    report.save(&[chart], &ctx.options.out, "fig10")?;
    report.tables.push(table);
    Ok(report)
}

/// One surface's curves (in the palette's colour `color`): Müser's non-adhesive area over the reduced loads `reduced` (E* ḡ
/// `e_g` [Pa]), and the BEM's without (`plain`) and with adhesion (`sticky`), at gradient `g`.
fn draw(
    chart: &mut Chart,
    (g, color): (f64, usize),
    (plain, sticky): (&challenge::Outcome, &challenge::Outcome),
    reduced: &[f64],
    e_g: f64,
) {
    let color = PALETTE[color];
    let (lo, hi) = (reduced[0] * 0.8, reduced[reduced.len() - 1] * 1.25);
    chart.curves.push(Curve::new(
        format!("Müser (no adhesion), ḡ = {g}"),
        (0..=50)
            .map(|k| {
                let r = lo * (hi / lo).powf(k as f64 / 50.0);
                (r * e_g * 1e-3, muser_area(r, 2.0))
            })
            .collect(),
        Mark::Line,
        color,
    ));
    chart.curves.push(Curve::solved(
        format!("BEM no adhesion, ḡ = {g}"),
        plain
            .points
            .iter()
            .map(|p| (p.mean_pressure * 1e-3, p.contact_area_fraction, p.converged))
            .collect(),
        Mark::Triangles,
        color,
    ));
    chart.curves.push(Curve::solved(
        format!("BEM adhesion μ = 3, ḡ = {g}"),
        sticky
            .points
            .iter()
            .map(|p| (p.mean_pressure * 1e-3, p.contact_area_fraction, p.converged))
            .collect(),
        Mark::Dots,
        color,
    ));
}

/// The paper's factor of 2 to 3 against what the lightest load shows (`gains`: over Müser's
/// curve and over our non-adhesive run, per gradient), and why the grid does not explain the
/// difference.
fn gain_note(
    ctx: &Context,
    gains: &[(f64, f64)],
    works: &[(f64, f64)],
    out: &[challenge::Outcome],
) -> String {
    let gradients = GRADIENTS;
    format!(
        "The paper states that at small pressures adhesion raises the contact area by a factor of 2 to 3. Here, at \
     the lightest load: {}. {}Adhesion enlarges each contact spot towards the JKR size of its asperity, and \
     an asperity of the local radius has a JKR contact radius at zero load (9π w0 R²/(2E*))^(1/3) of {}, \
     so a spot's growth is barely resolved here; but the grid is not what separates us from the paper: on \
     full mode's ḡ = 1 surface (512², gain 1.03) refined to 1024² and 2048², 2.8 cells a JKR radius, the gain \
     over our non-adhesive run rises only to 1.04 and 1.06 (`TABOR=3 cargo xtask study challenge-mesh`, \
     docs/validation.md). On cells this coarse the law traps, and the solver's path picks the state: on the \
     challenge at 1024² with the exponential law, at the same mean gap, Tamaas's iteration lands in one with \
     1.43 times our quasi-static area and a start with every overlapping cell on the wall in one with 2.6 \
     times (docs/performance.md), and Fig. 8's unloading branch holds 1.3-3.5 times the loading area. \
     States off the quasi-static loading path may be where the paper's factor comes from; that is not \
     measured on this figure.",
        gradients
            .iter()
            .zip(gains)
            .map(|(g, (muser, own))| {
                format!("ḡ = {g}: {muser:.2} over Müser's curve, {own:.2} over our non-adhesive run")
            })
            .collect::<Vec<_>>()
            .join("; "),
        match ctx.options.challenge_law {
            case::LawKind::Surface => "",
            _ => "The law is not the paper's (its Lennard-Jones surface law). ",
        },
        gradients
            .iter()
            .zip(works)
            .zip(out.iter().step_by(2))
            .map(|((g, &(w0, radius)), o)| {
                let a0 = theory::jkr_dmt::jkr_zero_load_radius(radius, w0, challenge::MODULUS);
                format!("{:.0} nm or {:.1} cells at ḡ = {g}", a0 * 1e9, a0 / o.cell)
            })
            .collect::<Vec<_>>()
            .join(" and ")
    )
}
