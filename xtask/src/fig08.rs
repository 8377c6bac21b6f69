//! Fig. 8: relative contact area of the contact-mechanics challenge surface against the
//! reduced pressure p/(E* g_bar), without and with adhesion, beside Persson's and Müser's
//! formulas, on a ladder of grids up to the challenge's own 4096^2.

use crate::challenge::{self, Run};
use crate::plot::{Chart, Curve, GREY, Mark, PALETTE, lighter};
use crate::{Context, FigureReport, Table};
use anyhow::Result;
use theory::rough::{muser_area, persson_area};

/// The loads of Figs. 8-9 (reduced pressures) and the challenge's reference load 0.01.
pub fn loads(ctx: &Context) -> Vec<f64> {
    ctx.pick(
        vec![0.0025, 0.005, 0.01, 0.02, 0.04],
        vec![0.00125, 0.0025, 0.005, 0.01, 0.02, 0.04, 0.08],
    )
}

/// The grids of Figs. 8-9, coarsest first, each surface with its own short cut-off
/// ([`challenge::cutoff`]): the finest is the challenge's 4096^2 with the specification's
/// 0.1 um, the coarser ones show how the curves move with resolution. A user's topography
/// is one grid, its own.
pub fn grids(ctx: &Context) -> Vec<usize> {
    if ctx.options.challenge_surface.is_some() {
        return vec![ctx.pick(256, 1024)];
    }
    ctx.pick(vec![128, 256], vec![1024, 2048, 4096])
}

/// The runs of Figs. 8-9, two a grid in the order of [`grids`]: without and with adhesion
/// (`Options::challenge_law`). The coarsest grid's adhesive run is unloaded again from the
/// heaviest load through the others (on the finer grids that branch would double the cost).
pub fn runs(ctx: &Context) -> Vec<Run> {
    let back: Vec<f64> = loads(ctx).into_iter().rev().skip(1).collect();
    grids(ctx)
        .into_iter()
        .enumerate()
        .flat_map(|(i, n)| {
            let base = challenge::case(n, 1.0, ctx.options.challenge_surface.as_ref());
            let sticky = challenge::adhesive(base.clone(), challenge::WORK, ctx.options.challenge_law);
            let unloading = if i == 0 { back.clone() } else { Vec::new() };
            [(base, Vec::new()), (sticky, unloading)].map(|(case, unloading)| Run {
                case,
                reduced: loads(ctx),
                unloading,
                profile_at: Some(0.01),
            })
        })
        .collect()
}

/// One grid's pair of outcomes: without and with adhesion.
pub struct Rung<'a> {
    pub n: usize,
    pub plain: &'a challenge::Outcome,
    pub sticky: &'a challenge::Outcome,
}

/// The outcomes of [`runs()`] as rungs, coarsest first.
pub fn rungs<'a>(ctx: &Context, out: &'a [challenge::Outcome]) -> Vec<Rung<'a>> {
    grids(ctx)
        .into_iter()
        .zip(out.chunks(2))
        .map(|(n, pair)| Rung {
            n,
            plain: &pair[0],
            sticky: &pair[1],
        })
        .collect()
}

/// What was computed, shared by Figs. 8 and 9.
pub fn computed(ctx: &Context, rungs: &[Rung]) -> Vec<String> {
    let law = ctx.options.challenge_law;
    let zone = challenge::process_zone(challenge::WORK, law);
    let mut v = vec![match &ctx.options.challenge_surface {
        Some(p) => format!(
            "The user's challenge topography {} (RMS gradient {:.3}).",
            p.display(),
            rungs[0].plain.rms_gradient
        ),
        None => format!(
            "Surface generated from the challenge's specification (the original file is not available here): \
             periodic, L = 100 µm, H = 0.8, roll-off 20 µm, RMS gradient 1, seed 1, on {} cells{}, the short \
             cut-off the specification's 0.1 µm or four cells, whichever is longer.",
            rungs
                .iter()
                .map(|r| format!("{}²", r.n))
                .collect::<Vec<_>>()
                .join(", "),
            if ctx.quick() {
                " (quick mode; the full mode's are 1024², 2048² and 4096²)"
            } else {
                ""
            },
        ),
    }];
    for r in rungs {
        let o = r.plain;
        let cutoff = match ctx.options.challenge_surface {
            Some(_) => String::new(),
            None => format!("short cut-off {:.2} µm, ", challenge::cutoff(r.n) * 1e6),
        };
        v.push(format!(
            "On {}: {cutoff}Rq = {:.3} µm, local radius (inverse RMS curvature) {:.2} µm, Tabor parameter \
             (R w0²/(E*² z0³))^(1/3) = {:.1} with R the local radius, cells {:.1} nm = {:.0} process zones.",
            grid_name(ctx, r.n),
            o.rms_height * 1e6,
            o.local_radius * 1e6,
            challenge::tabor(o.local_radius, challenge::WORK),
            o.cell * 1e9,
            o.cell / zone,
        ));
    }
    v.push(format!(
        "E* = 25 MPa; adhesion of w0 = 50 mJ/m² by {}; process zone E* w0/σ0² = {:.2} nm. Load control, \
         increasing loads, warm-started, then (adhesion, on {} only) back down through the same loads; \
         tolerances 1e-8 (no adhesion) and 1e-6 of the range (adhesion).",
        challenge::describe(law),
        zone * 1e9,
        grid_name(ctx, rungs[0].n),
    ));
    for r in rungs {
        for o in [r.plain, r.sticky] {
            v.extend(
                o.warnings
                    .iter()
                    .map(|w| format!("Solver warning ({}): {w}", grid_name(ctx, r.n))),
            );
        }
    }
    v
}

/// A rung's name in the text: its grid, or the user's topography.
pub fn grid_name(ctx: &Context, n: usize) -> String {
    match ctx.options.challenge_surface {
        Some(_) => "the topography".into(),
        None => format!("{n}²"),
    }
}

pub fn run(ctx: &Context) -> Result<FigureReport> {
    let runs = runs(ctx);
    let out = challenge::outcomes(ctx, &runs)?;
    let rungs = rungs(ctx, &out);
    let mut report = FigureReport::new(
        8,
        "Contact-mechanics challenge: relative contact area vs p/(E* g_bar)",
    );
    report.computed = computed(ctx, &rungs);
    let mut table = Table::new(
        "fig08",
        &[
            "grid_n",
            "p_over_e_star_g_bar",
            "area_fraction_no_adhesion",
            "area_fraction_adhesion",
            "area_fraction_adhesion_unloading",
            "area_fraction_persson",
            "area_fraction_muser_k2",
            "converged_both",
        ],
    );
    let dense: Vec<f64> = (0..=60)
        .map(|k| {
            loads(ctx)[0] * 0.8 * (loads(ctx).last().unwrap() / loads(ctx)[0] * 1.5).powf(k as f64 / 60.0)
        })
        .collect();
    let mut chart = Chart::new(
        "Contact-mechanics challenge surface",
        "reduced pressure p/(E* ḡ)",
        "relative contact area a_r",
    );
    chart.x_log = true;
    chart.y_log = true;
    chart.curves.push(Curve::new(
        "Persson erf(√2 p/(E*ḡ))",
        dense.iter().map(|&r| (r, persson_area(r))).collect(),
        Mark::Dashed,
        GREY,
    ));
    chart.curves.push(Curve::new(
        "Müser, Eq. 14, k = 2",
        dense.iter().map(|&r| (r, muser_area(r, 2.0))).collect(),
        Mark::Line,
        GREY,
    ));
    let law = ctx.options.challenge_law;
    let zone = challenge::process_zone(challenge::WORK, law);
    let last = rungs.len() - 1;
    for (i, r) in rungs.iter().enumerate() {
        // The finest grid in full colour, the coarser ones paler.
        let shade = 0.55 * (last - i) as f64 / last.max(1) as f64;
        let name = grid_name(ctx, r.n);
        // The unloading branch at each load, from its turning point (the heaviest load) down.
        let top = r.sticky.points.last().expect("at least one load");
        let back: Vec<&challenge::LoadPoint> = if r.sticky.unloading.is_empty() {
            Vec::new()
        } else {
            std::iter::once(top).chain(&r.sticky.unloading).collect()
        };
        let unloaded = |p: f64| back.iter().find(|u| u.reduced == p);
        for (a, b) in r.plain.points.iter().zip(&r.sticky.points) {
            let u = unloaded(a.reduced);
            table.push(vec![
                r.n as f64,
                a.reduced,
                a.contact_area_fraction,
                b.contact_area_fraction,
                u.map_or(f64::NAN, |u| u.contact_area_fraction),
                persson_area(a.reduced),
                muser_area(a.reduced, 2.0),
                (a.converged && b.converged && u.is_none_or(|u| u.converged)) as u8 as f64,
            ]);
            report.solver_seconds += a.wall_time_s + b.wall_time_s;
        }
        report.solver_seconds += r.sticky.unloading.iter().map(|u| u.wall_time_s).sum::<f64>();
        chart.curves.push(Curve::solved(
            format!("BEM, no adhesion, {name}"),
            solved(&r.plain.points),
            Mark::Triangles,
            lighter(PALETTE[0], shade),
        ));
        chart.curves.push(Curve::solved(
            format!("BEM, adhesion ({}), {name}", challenge::label(law)),
            solved(&r.sticky.points),
            Mark::Dots,
            lighter(PALETTE[3], shade),
        ));
        if !back.is_empty() {
            chart.curves.push(Curve::solved(
                format!(
                    "BEM, adhesion, unloading, {name} ({})",
                    if r.sticky.cell > zone {
                        "lattice-trapped: cells far coarser than the process zone"
                    } else {
                        "cells within the process zone"
                    }
                ),
                solved(back.iter().copied()),
                Mark::Line,
                lighter(PALETTE[3], shade),
            ));
        }
        agreement(&mut report, &name, r, &back, zone);
    }
    report.save(&[chart], &ctx.options.out, "fig08")?;
    if rungs.len() > 1 {
        report.agreement.push(resolution(ctx, &rungs));
    }
    report.tables.push(table);
    let finest = &rungs[last];
    report.claim =
        "On the contact-mechanics challenge at 4096², the BEM's non-adhesive areas agree with the GFMD \
                    and FFT-BVM references, and the Lennard-Jones surface law adds the adhesive area."
            .into();
    report.verdict = format!(
        "Partly reproduced: the non-adhesive areas are (slope {:.2} on {} against the references' near 2); the \
         adhesive ones come from {} on cells {:.0} process zones wide{}, and the unloading line is a property of \
         the grid.",
        small_load_slope(finest.plain),
        grid_name(ctx, finest.n),
        match law {
            case::LawKind::Surface => "the paper's law",
            _ => "another law than the paper's",
        },
        finest.sticky.cell / zone,
        if finest.sticky.cell > 1.01 * challenge::LENGTH / 4096.0 {
            ", not at the paper's 4096²"
        } else {
            ", the paper's 4096² grid"
        },
    );
    Ok(report)
}

/// A curve's points and whether each converged.
fn solved<'a>(points: impl IntoIterator<Item = &'a challenge::LoadPoint>) -> Vec<(f64, f64, bool)> {
    points
        .into_iter()
        .map(|p| (p.reduced, p.contact_area_fraction, p.converged))
        .collect()
}

/// Small-load slope a_r / p~ over the two lightest loads.
fn small_load_slope(plain: &challenge::Outcome) -> f64 {
    plain.points[..2]
        .iter()
        .map(|p| p.contact_area_fraction / p.reduced)
        .sum::<f64>()
        / 2.0
}

/// One grid's agreement: the non-adhesive slope and Müser, adhesion's gain, the unloading.
fn agreement(report: &mut FigureReport, name: &str, r: &Rung, back: &[&challenge::LoadPoint], zone: f64) {
    let (plain, sticky) = (r.plain, r.sticky);
    // The name opens a sentence: "The topography", not "the topography".
    let mut chars = name.chars();
    let name = &chars.next().map_or(String::new(), |c| {
        c.to_uppercase().chain(chars).collect::<String>()
    });
    let muser_dev = plain
        .points
        .iter()
        .map(|p| (p.contact_area_fraction / muser_area(p.reduced, 2.0) - 1.0).abs())
        .fold(0.0, f64::max);
    let gain: Vec<String> = plain
        .points
        .iter()
        .zip(&sticky.points)
        .map(|(a, b)| format!("{:.2}", b.contact_area_fraction / a.contact_area_fraction))
        .collect();
    report.agreement.push(format!(
        "{name}: no adhesion, small-load slope a_r/(p/(E*ḡ)) = {:.2} (literature's BEM and GFMD: near 2; \
         Persson: {:.2}), Müser's formula with k = 2 within {:.0} % over all loads; adhesion enlarges the \
         contact area by factors {} from the lightest load to the heaviest; {} of {} adhesive loads converged.",
        small_load_slope(plain),
        (8.0 / std::f64::consts::PI).sqrt(),
        100.0 * muser_dev,
        gain.join(", "),
        sticky.points.iter().filter(|p| p.converged).count(),
        sticky.points.len()
    ));
    if back.is_empty() {
        return;
    }
    let held: Vec<f64> = sticky
        .unloading
        .iter()
        .filter_map(|u| {
            let on_loading = sticky.points.iter().find(|p| p.reduced == u.reduced)?;
            Some(u.contact_area_fraction / on_loading.contact_area_fraction)
        })
        .collect();
    let zones = sticky.cell / zone;
    // Cells far larger than the process zone each snap in and hold on alone (docs/validation.md,
    // `roughcontact sweep`): the area is trapped, not the quasi-static answer.
    let trapped = held.last().is_some_and(|&h| h > 1.5) && zones > 1.0;
    report.agreement.push(format!(
        "{name}, unloading (load control, from the heaviest load back down, each load warm-started): {} of {} \
         loads converged; contact area on unloading over loading {} from the heaviest to the lightest. {}",
        sticky.unloading.iter().filter(|p| p.converged).count(),
        sticky.unloading.len(),
        held.iter().map(|h| format!("{h:.2}")).collect::<Vec<_>>().join(", "),
        if trapped {
            format!(
                "On cells {zones:.0} times the adhesive process zone E* w0/σ0² = {:.1} nm a cell once in \
                 contact holds on, so the area hardly shrinks: lattice trapping, not the hysteresis a resolved \
                 surface would show.",
                zone * 1e9
            )
        } else {
            format!("Cells are {zones:.1} times the adhesive process zone.")
        }
    ));
}

/// How the areas move from each grid to the finest, without and with adhesion.
fn resolution(ctx: &Context, rungs: &[Rung]) -> String {
    let finest = rungs.last().expect("a grid");
    let range = |coarse: &challenge::Outcome, fine: &challenge::Outcome| {
        let d: Vec<f64> = coarse
            .points
            .iter()
            .zip(&fine.points)
            .map(|(a, b)| 100.0 * (a.contact_area_fraction / b.contact_area_fraction - 1.0))
            .collect();
        let lo = d.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        format!("{lo:+.1} to {hi:+.1} %")
    };
    let parts: Vec<String> = rungs[..rungs.len() - 1]
        .iter()
        .map(|r| {
            format!(
                "{}: {} without adhesion, {} with it",
                grid_name(ctx, r.n),
                range(r.plain, finest.plain),
                range(r.sticky, finest.sticky)
            )
        })
        .collect();
    format!(
        "Resolution (each grid's surface carries its own short cut-off, so the surfaces differ in their \
         finest waves, not only the mesh): loading areas against {}'s, load by load, {}.",
        grid_name(ctx, finest.n),
        parts.join("; ")
    )
}
