//! `theory`: reference curves as CSV, and their characteristic numbers.

use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use theory::maugis::MaugisDugdale;

#[derive(Args, Debug)]
pub struct TheoryArgs {
    #[command(subcommand)]
    model: Model,
    /// Write the curve to this CSV file instead of standard output.
    #[arg(short, long, global = true)]
    output: Option<PathBuf>,
    /// Print the model's characteristic numbers instead of the curve (maugis, jkr, dmt,
    /// greenwood, wavy, layer; sticky prints only those).
    #[arg(long, global = true)]
    summary: bool,
    /// With --summary: as JSON (snake_case keys).
    #[arg(long, global = true)]
    json: bool,
    /// Points on the curve [default: 200] (not for greenwood, whose steps follow --resolution).
    #[arg(long, global = true)]
    points: Option<usize>,
    /// Largest dimensionless contact radius A on the curve (the compressive end) [default: 3]
    /// (maugis, jkr, dmt).
    #[arg(long, global = true)]
    max_radius: Option<f64>,
    /// Also draw the curve (load against approach) as a PNG (not for sticky).
    #[arg(long, global = true, value_name = "FILE")]
    plot: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Model {
    /// Maugis-Dugdale sphere: A = a/(pi w0 R^2/K)^(1/3), P = load/(pi w0 R),
    /// D = approach/(pi^2 w0^2 R/K^2)^(1/3), K = 4E*/3.
    Maugis {
        /// Maugis' parameter lambda (> 0); or give --tabor.
        #[arg(long)]
        lambda: Option<f64>,
        /// Tabor parameter mu of a Lennard-Jones law: lambda = 1.157 mu.
        #[arg(long)]
        tabor: Option<f64>,
    },
    /// JKR sphere in Maugis' units (the lambda -> infinity limit).
    Jkr,
    /// DMT sphere in Maugis' units (the lambda -> 0 limit).
    Dmt,
    /// Greenwood (1997): sphere with the full Lennard-Jones 9-3 law on an axisymmetric grid,
    /// traced by its central separation (S-curves whole). Load W/(2 pi R w0), approach
    /// alpha/z0 (zero when the undeformed apex is at z0), radii in sqrt(R z0).
    Greenwood {
        /// Tabor parameter mu = (R w0^2 / (E*^2 z0^3))^(1/3) (> 0).
        #[arg(long)]
        tabor: f64,
        /// Trace until the approach alpha/z0 exceeds this.
        #[arg(long, default_value_t = 3.0, allow_hyphen_values = true)]
        max_approach: f64,
        /// Central separation h(0)/z0 to start from (far apart).
        #[arg(long, default_value_t = 5.0)]
        from: f64,
        /// Largest change of approach (or load) between points [-].
        #[arg(long, default_value_t = 0.02)]
        resolution: f64,
        /// Ring width in units of sqrt(R z0) (default 0.02: pull-off converged to 1e-4).
        #[arg(long, default_value_t = 0.02)]
        ring_width: f64,
    },
    /// Hertz sphere: load, contact radius and peak pressure against approach (SI units).
    Hertz {
        /// Sphere radius R [m].
        #[arg(long)]
        radius: f64,
        /// Composite modulus E* [Pa].
        #[arg(long)]
        modulus: f64,
        /// Largest approach on the curve [m].
        #[arg(long)]
        max_approach: f64,
    },
    /// Rigid sphere on an elastic layer: the exact frictionless contact (Lebedev-Ufliand's
    /// equation by quadrature) beside Hertz, Dimitriadis et al. (2002)'s fit in
    /// chi = sqrt(R delta) / h (chi <~ 0.5, rigid bases) and, bonded, the thin compressible
    /// layer's Winkler limit P = pi M R delta^2 / h; rows step the contact radius. --summary
    /// with --work-of-adhesion: JKR's pull-off on the layer (SI units).
    #[command(allow_hyphen_values = true)]
    Layer {
        /// Sphere radius R [m].
        #[arg(long)]
        radius: f64,
        /// The layer's plane-strain modulus E* = E / (1 - nu^2) [Pa].
        #[arg(long)]
        modulus: f64,
        /// Layer thickness h [m].
        #[arg(long)]
        thickness: f64,
        /// The layer's Poisson's ratio nu [-], in (-1, 0.5].
        #[arg(long)]
        poisson: f64,
        /// How the layer meets its base.
        #[arg(long, value_enum, default_value = "bonded")]
        layer_base: case::LayerBase,
        /// With --layer-base elastic: the substrate's plane-strain modulus [Pa].
        #[arg(long)]
        substrate_modulus: Option<f64>,
        /// With --layer-base elastic: the substrate's Poisson's ratio [-].
        #[arg(long)]
        substrate_poisson: Option<f64>,
        /// Largest approach on the curve [m] (not with --summary).
        #[arg(long, required_unless_present = "summary")]
        max_approach: Option<f64>,
        /// Work of adhesion w [J/m^2]: with --summary, JKR's pull-off on the layer.
        #[arg(long)]
        work_of_adhesion: Option<f64>,
    },
    /// Rigid wave A cos(2 pi x / lambda) on an elastic half-space (plane strain): Westergaard's
    /// and Johnson's (1995) JKR mean pressure [Pa] against the contact strip's half-width a
    /// [m] (one strip per wavelength); the summary gives Johnson's alpha, the pull-off and the
    /// snap to complete contact. Compare `roughcontact sweep --example wavy-jkr`.
    Wavy {
        /// Amplitude A [m] (half the peak-to-valley height).
        #[arg(long)]
        amplitude: f64,
        /// Wavelength lambda [m].
        #[arg(long)]
        wavelength: f64,
        /// Composite modulus E* [Pa].
        #[arg(long)]
        modulus: f64,
        /// Work of adhesion w0 [J/m^2] (0: Westergaard's problem alone).
        #[arg(long, default_value_t = 0.0)]
        work_of_adhesion: f64,
    },
    /// Rigid sphere on a viscoelastic half-space without adhesion (a generalized Maxwell
    /// solid): pressed in at --rate until --rise-time and drawn back at the same rate (Lee &
    /// Radok while the contact grows, Ting after), or with --load a load put on at once (Lee &
    /// Radok's creep); beside the relaxed and glassy Hertz loads (SI units).
    #[command(allow_hyphen_values = true)]
    Viscoelastic {
        /// Sphere radius R [m].
        #[arg(long)]
        radius: f64,
        /// Relaxed (long-time) plane-strain modulus E*_inf [Pa].
        #[arg(long)]
        modulus: f64,
        /// The branches' moduli E_k [Pa], comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        maxwell_moduli: Vec<f64>,
        /// The branches' relaxation times tau_k [s], comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        maxwell_times: Vec<f64>,
        /// Approach rate [m/s] (with --rise-time).
        #[arg(long, requires = "rise_time", conflicts_with = "load")]
        rate: Option<f64>,
        /// Time of the deepest approach [s]; the curve runs to twice it.
        #[arg(long, requires = "rate")]
        rise_time: Option<f64>,
        /// A load [N] put on at time 0 and held (creep), instead of a rate.
        #[arg(long, required_unless_present = "rate")]
        load: Option<f64>,
        /// With --load: the curve's end [s] [default: ten times the slowest creep time].
        #[arg(long, requires = "load")]
        duration: Option<f64>,
    },
    /// Relative contact area of a nominally flat rough surface against the reduced pressure
    /// p/(E* g_bar): Persson's erf law and Müser's formula (the paper's Eq. 14, corrected).
    Area {
        /// Müser's prefactor k (the small-load slope).
        #[arg(long, default_value_t = 2.0)]
        k: f64,
        /// Largest reduced pressure p/(E* g_bar) on the curve.
        #[arg(long, default_value_t = 1.0)]
        max_pressure: f64,
    },
    /// Stickiness of a self-affine surface (Eq. 13 spectrum): the modified Johnson parameter
    /// (Eq. 15), Ciavarella's variable and criterion (Eq. 16) and Persson-Tosatti's effective
    /// work of adhesion, from plain numbers (take them from `roughcontact stats`).
    Sticky {
        /// Work of adhesion w0 [J/m^2].
        #[arg(long)]
        work_of_adhesion: f64,
        /// Composite modulus E* [Pa].
        #[arg(long)]
        modulus: f64,
        /// RMS height Rq [m].
        #[arg(long)]
        rms_height: f64,
        /// Hurst exponent H [-].
        #[arg(long, default_value_t = 0.8)]
        hurst: f64,
        /// Longest wavelength lambda_L [m] (the box).
        #[arg(long)]
        long_wavelength: f64,
        /// Roll-off wavelength [m] (default: lambda_L, no plateau).
        #[arg(long)]
        rolloff_wavelength: Option<f64>,
        /// Shortest wavelength [m].
        #[arg(long)]
        short_wavelength: f64,
    },
}

fn hertz(a: &TheoryArgs, r: f64, e: f64, max: f64) -> Result<()> {
    if !(r > 0.0 && e > 0.0 && max > 0.0 && r.is_finite() && e.is_finite() && max.is_finite()) {
        bail!("--radius, --modulus and --max-approach must be finite and > 0");
    }
    let mut out = open(a)?;
    writeln!(out, "approach_m,load_n,contact_radius_m,max_pressure_pa")?;
    let mut pts = Vec::new();
    for k in 0..a.points() {
        let d = max * k as f64 / (a.points() - 1) as f64;
        let w = theory::hertz::load_of_approach(d, r, e);
        let c = (r * d).sqrt();
        let p0 = if c > 0.0 {
            3.0 * w / (2.0 * std::f64::consts::PI * c * c)
        } else {
            0.0
        };
        writeln!(out, "{d:e},{w:e},{c:e},{p0:e}")?;
        pts.push((d, w));
    }
    if let Some(path) = &a.plot {
        draw(path, "Hertz", "approach [m]", "load [N]", pts)?;
    }
    Ok(())
}

/// The sphere on a layer: `--radius`, `--modulus`, `--thickness` and `--poisson`, the base,
/// and the largest approach or (with `--summary`) the work of adhesion.
struct LayerSphere {
    r: f64,
    e: f64,
    layer: elastic::Layer,
}

fn layer_of(
    (r, e, h, nu): (f64, f64, f64, f64),
    base: case::LayerBase,
    substrate: (Option<f64>, Option<f64>),
) -> Result<LayerSphere> {
    for (name, v) in [("--radius", r), ("--modulus", e)] {
        if !(v.is_finite() && v > 0.0) {
            bail!("{name} must be finite and > 0, got {v}");
        }
    }
    let base = match (base, substrate) {
        (case::LayerBase::Bonded, (None, None)) => elastic::Base::Bonded,
        (case::LayerBase::Frictionless, (None, None)) => elastic::Base::Frictionless,
        (case::LayerBase::Elastic, (Some(e_star), Some(poisson))) => {
            elastic::Base::Substrate { e_star, poisson }
        }
        (case::LayerBase::Elastic, _) => {
            bail!("--layer-base elastic needs --substrate-modulus [Pa] and --substrate-poisson")
        }
        _ => bail!("--substrate-modulus and --substrate-poisson are a coating's: give --layer-base elastic"),
    };
    let layer = elastic::Layer::new(h, nu, base).map_err(|e| match e {
        elastic::ElasticError::InvalidParameter { name, value, reason } => {
            anyhow::anyhow!("--{} {reason}, got {value}", name.replace('_', "-"))
        }
        other => other.into(),
    })?;
    Ok(LayerSphere { r, e, layer })
}

fn layer(a: &TheoryArgs, s: &LayerSphere, max: Option<f64>, w: Option<f64>) -> Result<()> {
    let (r, e, h, nu) = (s.r, s.e, s.layer.thickness, s.layer.poisson);
    let body = theory::layer::LayerContact::new(h, e, |x| s.layer.compliance_ratio(x / h, e));
    let mut out = open(a)?;
    if a.summary {
        let Some(w) = w.filter(|w| w.is_finite() && *w > 0.0) else {
            bail!("--summary for `theory layer` is JKR's pull-off: give --work-of-adhesion > 0 [J/m^2]");
        };
        let off = body.pull_off(r, w);
        let half = theory::jkr_dmt::jkr_pull_off_load_control(r, w);
        let a_half = (9.0 * std::f64::consts::PI * w * r * r / (8.0 * e)).cbrt();
        if a.json {
            let v = json!({
                "model": "layer", "units": "loads in N (tensile < 0), lengths in m",
                "pull_off_load": off.load,
                "pull_off_contact_radius": off.radius,
                "pull_off_approach": off.approach,
                "half_space_pull_off_load": half,
                "half_space_pull_off_contact_radius": a_half,
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "JKR sphere on a layer (exact Griffith balance)")?;
            writeln!(
                out,
                "pull-off load          {:.6e} N at contact radius {:.4e} m, approach {:.4e} m",
                off.load, off.radius, off.approach
            )?;
            writeln!(
                out,
                "on the half-space      {half:.6e} N at contact radius {a_half:.4e} m (the layer's is {:.4} times it)",
                off.load / half
            )?;
        }
        return Ok(());
    }
    if w.is_some() {
        bail!("--work-of-adhesion gives JKR's pull-off on the layer: add --summary");
    }
    let max = max.unwrap_or(f64::NAN);
    if !(max.is_finite() && max > 0.0) {
        bail!("--max-approach must be finite and > 0, got {max}");
    }
    let rigid = match s.layer.base {
        elastic::Base::Bonded => Some(theory::layer::Base::Bonded),
        elastic::Base::Frictionless => Some(theory::layer::Base::Frictionless),
        elastic::Base::Substrate { .. } => None,
    };
    writeln!(
        out,
        "approach_m,chi,dimitriadis_load_n,hertz_load_n,winkler_load_n,load_n,contact_radius_m"
    )?;
    let (mut exact, mut fitted, mut hertz) = (Vec::new(), Vec::new(), Vec::new());
    // Rows step the contact radius: one solve a row (an approach would take a root search).
    // Past the widest contact the exact solution evaluates, the rest of the rows step the
    // approach with its columns left empty.
    let points = a.points();
    let a_max = body.hertz(max, r).radius;
    let (radial, reach) = if a_max.is_nan() {
        (points / 2, theory::layer::REACH * h)
    } else {
        (points, a_max)
    };
    let d_reach = body.sphere(reach, r, 0.0).approach;
    for k in 0..points {
        let (c, d, p) = if k == 0 {
            (0.0, 0.0, 0.0)
        } else if k < radial {
            let c = reach * k as f64 / (radial - 1) as f64;
            let s = body.sphere(c, r, 0.0);
            (c, s.approach, s.load)
        } else {
            let f = (k + 1 - radial) as f64 / (points - radial) as f64;
            (f64::NAN, d_reach + f * (max - d_reach), f64::NAN)
        };
        let chi = (r * d).sqrt() / h;
        let fit = rigid.map(|base| theory::layer::dimitriadis_load(d, r, h, e, nu, base));
        let w_h = theory::hertz::load_of_approach(d, r, e);
        // Winkler's bed is the bonded compressible layer's thin limit.
        let winkler = (rigid == Some(theory::layer::Base::Bonded) && nu < 0.5)
            .then(|| theory::layer::winkler_load(d, r, h, e, nu));
        let blank = |v: Option<f64>| v.map(|v| format!("{v:e}")).unwrap_or_default();
        let number = |v: f64| (!v.is_nan()).then_some(v);
        writeln!(
            out,
            "{d:e},{chi:e},{},{w_h:e},{},{},{}",
            blank(fit),
            blank(winkler),
            blank(number(p)),
            blank(number(c))
        )?;
        if !p.is_nan() {
            exact.push((d, p));
        }
        hertz.push((d, w_h));
        if let Some(f) = fit {
            fitted.push((d, f));
        }
    }
    if let Some(path) = &a.plot {
        let mut curves = vec![("exact", exact), ("Hertz", hertz)];
        if !fitted.is_empty() {
            curves.push(("Dimitriadis", fitted));
        }
        draw_curves(path, "sphere on a layer", "approach [m]", "load [N]", curves)?;
    }
    Ok(())
}

fn viscoelastic(
    a: &TheoryArgs,
    r: f64,
    solid: &theory::viscoelastic::Maxwell,
    history: History,
) -> Result<()> {
    use theory::viscoelastic::hertz_limit;
    let (relaxed, glassy) = (solid.relaxed, solid.glassy());
    let mut out = open(a)?;
    let (mut curve, mut slow, mut fast) = (Vec::new(), Vec::new(), Vec::new());
    match history {
        History::Rate { rate, rise } => {
            writeln!(
                out,
                "time_s,approach_m,contact_radius_m,load_n,relaxed_hertz_n,glassy_hertz_n"
            )?;
            for k in 0..a.points() {
                let t = 2.0 * rise * k as f64 / (a.points() - 1) as f64;
                let d = rate * if t <= rise { t } else { 2.0 * rise - t };
                let (c, p) = theory::viscoelastic::triangle(solid, t, r, rate, rise);
                let (p_slow, p_fast) = (hertz_limit(d, r, relaxed), hertz_limit(d, r, glassy));
                writeln!(out, "{t:e},{d:e},{c:e},{p:e},{p_slow:e},{p_fast:e}")?;
                curve.push((d, p));
                slow.push((d, p_slow));
                fast.push((d, p_fast));
            }
        }
        History::Load { load, duration } => {
            writeln!(
                out,
                "time_s,contact_radius_m,approach_m,relaxed_radius_m,glassy_radius_m"
            )?;
            let hertz = |e: f64| (0.75 * load * r / e).cbrt();
            for k in 0..a.points() {
                let t = duration * k as f64 / (a.points() - 1) as f64;
                let c = theory::viscoelastic::creep_radius(solid, t, r, load);
                writeln!(
                    out,
                    "{t:e},{c:e},{:e},{:e},{:e}",
                    c * c / r,
                    hertz(relaxed),
                    hertz(glassy)
                )?;
                curve.push((t, c * c / r));
            }
        }
    }
    if let Some(path) = &a.plot {
        match history {
            History::Rate { .. } => draw_curves(
                path,
                "viscoelastic sphere",
                "approach [m]",
                "load [N]",
                vec![("Lee-Radok / Ting", curve), ("relaxed", slow), ("glassy", fast)],
            )?,
            History::Load { .. } => draw(path, "creep of a sphere", "time [s]", "approach [m]", curve)?,
        }
    }
    Ok(())
}

/// What `theory viscoelastic` traces.
#[derive(Clone, Copy)]
enum History {
    /// In at `rate` \[m/s\] until `rise` \[s\], out at the same rate until `2 rise`.
    Rate { rate: f64, rise: f64 },
    /// `load` \[N\] held from 0 to `duration` \[s\].
    Load { load: f64, duration: f64 },
}

fn area(a: &TheoryArgs, k: f64, max: f64) -> Result<()> {
    if !(k > 0.0 && max > 0.0 && k.is_finite() && max.is_finite()) {
        bail!("--k and --max-pressure must be finite and > 0");
    }
    let mut out = open(a)?;
    writeln!(out, "reduced_pressure,persson,muser")?;
    let (mut p1, mut p2) = (Vec::new(), Vec::new());
    for i in 0..a.points() {
        let x = max * i as f64 / (a.points() - 1) as f64;
        let (ap, am) = (theory::rough::persson_area(x), theory::rough::muser_area(x, k));
        writeln!(out, "{x:e},{ap:e},{am:e}")?;
        p1.push((x, ap));
        p2.push((x, am));
    }
    if let Some(path) = &a.plot {
        draw_curves(
            path,
            "relative contact area",
            "p / (E* g_bar)",
            "a_r",
            vec![("Persson", p1), ("Müser", p2)],
        )?;
    }
    Ok(())
}

/// The stickiness criteria for a material (`w0` [J/m^2], `e` = E* [Pa]) and a self-affine
/// spectrum whose longest wavelength is `long` [m].
fn sticky(
    a: &TheoryArgs,
    w0: f64,
    e: f64,
    long: f64,
    spectrum: &theory::rough::SelfAffineSpectrum,
) -> Result<()> {
    use theory::rough::{ciavarella_sticky, ciavarella_variable, johnson_parameter, persson_tosatti_work};
    let (rq, hurst) = (spectrum.rms_height, spectrum.hurst);
    let gradient = spectrum.moment(2.0).sqrt();
    let johnson = johnson_parameter(w0, e, rq, spectrum.q_long, spectrum.q_short, hurst);
    let ciavarella = ciavarella_variable(rq, e, long, w0);
    let pt = persson_tosatti_work(w0, e, spectrum.moment(1.0), gradient);
    let mut out = open(a)?;
    if a.json {
        let v = json!({
            "rms_gradient": gradient, "johnson_parameter": johnson,
            "ciavarella_variable": ciavarella, "ciavarella_sticky": ciavarella_sticky(rq, e, long, w0),
            "persson_tosatti_work": pt, "persson_tosatti_sticky": pt > 0.0,
            "units": "persson_tosatti_work in J/m^2; the others dimensionless",
        });
        writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
    } else {
        writeln!(out, "RMS gradient                      {gradient:.6e}")?;
        writeln!(out, "modified Johnson parameter        {johnson:.6e}")?;
        writeln!(
            out,
            "Ciavarella's Rq^2 E*/(lambda_L w0) {ciavarella:.6e} (sticky below 0.6: {})",
            ciavarella_sticky(rq, e, long, w0)
        )?;
        writeln!(
            out,
            "Persson-Tosatti effective work    {pt:.6e} J/m^2 (sticky when > 0: {})",
            pt > 0.0
        )?;
    }
    Ok(())
}

fn wavy(a: &TheoryArgs, w: &theory::wavy::Wave) -> Result<()> {
    let lengths = [w.amplitude, w.wavelength, w.e_star];
    if !(lengths.iter().all(|v| v.is_finite() && *v > 0.0)
        && w.work_of_adhesion.is_finite()
        && w.work_of_adhesion >= 0.0)
    {
        bail!("--amplitude, --wavelength and --modulus must be finite and > 0, --work-of-adhesion >= 0");
    }
    let mut out = open(a)?;
    let p_star = w.full_contact_pressure();
    if a.summary {
        let adhesive = w.work_of_adhesion > 0.0;
        let (pull_off, a_pull) = w.jkr_pull_off();
        let (snap, a_snap) = w.jkr_snap_to_full_contact();
        if a.json {
            let v = json!({
                "model": "wavy", "units": "pressures in Pa (tensile < 0), half-widths in m",
                "full_contact_pressure": p_star,
                "crest_radius": w.crest_radius(),
                "johnson_parameter": w.johnson_alpha(),
                "jkr_pull_off_mean_pressure": adhesive.then_some(pull_off),
                "jkr_pull_off_half_width": adhesive.then_some(a_pull),
                "jkr_snap_mean_pressure": adhesive.then_some(snap),
                "jkr_snap_half_width": adhesive.then_some(a_snap),
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "Rigid wave on a half-space (Westergaard; Johnson 1995)")?;
            writeln!(out, "full-contact pressure p*    {p_star:.6e} Pa")?;
            writeln!(out, "crest radius                {:.6e} m", w.crest_radius())?;
            if adhesive {
                writeln!(out, "Johnson's alpha             {:.6}", w.johnson_alpha())?;
                writeln!(
                    out,
                    "JKR pull-off                {pull_off:.6e} Pa at half-width {a_pull:.4e} m"
                )?;
                writeln!(
                    out,
                    "JKR snap to full contact    {snap:.6e} Pa at half-width {a_snap:.4e} m{}",
                    if snap < 0.0 {
                        " (negative: the wave sticks once it touches)"
                    } else {
                        ""
                    }
                )?;
            }
        }
        return Ok(());
    }
    writeln!(
        out,
        "half_width_m,contact_fraction,westergaard_pressure_pa,jkr_pressure_pa"
    )?;
    let (mut p1, mut p2) = (Vec::new(), Vec::new());
    // Up to (not at) complete contact, where Johnson's correction diverges.
    for k in 0..a.points() {
        let half = 0.5 * w.wavelength * k as f64 / a.points() as f64;
        let (pw, pj) = (w.westergaard_pressure(half), w.jkr_pressure(half));
        let fraction = 2.0 * half / w.wavelength;
        writeln!(out, "{half:e},{fraction:e},{pw:e},{pj:e}")?;
        p1.push((fraction, pw / p_star));
        p2.push((fraction, pj / p_star));
    }
    if let Some(path) = &a.plot {
        draw_curves(
            path,
            &format!("rigid wave, Johnson's alpha = {:.3}", w.johnson_alpha()),
            "contact fraction 2a/lambda",
            "mean pressure p/p*",
            vec![("Westergaard", p1), ("JKR (Johnson 1995)", p2)],
        )?;
    }
    Ok(())
}

fn greenwood(
    a: &TheoryArgs,
    mu: f64,
    max_approach: f64,
    from: f64,
    resolution: f64,
    ring_width: f64,
) -> Result<()> {
    use theory::greenwood::{Greenwood, Mesh};
    if !(mu.is_finite() && mu > 0.0) {
        bail!("--tabor must be finite and > 0, got {mu}");
    }
    if !(from > 1.0 && resolution > 0.0 && ring_width > 0.0 && ring_width < 1.0 && max_approach.is_finite()) {
        bail!("need --from > 1, --resolution > 0, 0 < --ring-width < 1 and a finite --max-approach");
    }
    let mesh = Mesh {
        spacing: ring_width,
        ..Mesh::default()
    };
    let c = Greenwood::new(mu, mesh).curve(from, max_approach, resolution)?;
    let mut out = open(a)?;
    let jump = |k: Option<usize>| k.map(|k| c.points[k].approach);
    if a.summary {
        if a.json {
            let v = json!({
                "model": "greenwood", "tabor_parameter": mu,
                "units": "pull-off forces in 2 pi R w0, approaches in z0 (zero: undeformed apex at z0)",
                "pull_off_load_control": c.pull_off_load_control,
                "pull_off_displacement_control": c.pull_off_displacement_control,
                "jump_in_approach": jump(c.jump_in), "jump_out_approach": jump(c.jump_out),
                "points": c.points.len(),
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "Greenwood (Lennard-Jones sphere), mu = {mu}")?;
            writeln!(
                out,
                "pull-off under load control          {:.6} 2 pi R w0",
                c.pull_off_load_control
            )?;
            writeln!(
                out,
                "pull-off under displacement control  {:.6} 2 pi R w0",
                c.pull_off_displacement_control
            )?;
            if let (Some(i), Some(o)) = (jump(c.jump_in), jump(c.jump_out)) {
                writeln!(out, "jump in at approach                  {i:.4} z0")?;
                writeln!(out, "jump out at approach                 {o:.4} z0")?;
            }
        }
        return Ok(());
    }
    writeln!(out, "central_separation,approach,load,contact_radius")?;
    for p in &c.points {
        writeln!(
            out,
            "{:e},{:e},{:e},{:e}",
            p.central_separation, p.approach, p.load, p.contact_radius
        )?;
    }
    if let Some(path) = &a.plot {
        let pts = c.points.iter().map(|p| (p.approach, p.load)).collect();
        draw(
            path,
            &format!("Lennard-Jones sphere (Greenwood), mu = {mu}"),
            "approach alpha/z0",
            "load W/(2 pi R w0)",
            pts,
        )?;
    }
    Ok(())
}

fn open(a: &TheoryArgs) -> Result<Box<dyn Write>> {
    Ok(match &a.output {
        Some(p) => Box::new(std::fs::File::create(p)?),
        None => Box::new(std::io::stdout().lock()),
    })
}

fn draw(path: &std::path::Path, title: &str, x: &str, y: &str, points: Vec<(f64, f64)>) -> Result<()> {
    draw_curves(path, title, x, y, vec![("theory", points)])
}

/// Several labelled curves on one chart, coloured in turn.
fn draw_curves(
    path: &std::path::Path,
    title: &str,
    x: &str,
    y: &str,
    curves: Vec<(&'static str, Vec<(f64, f64)>)>,
) -> Result<()> {
    use crate::plot::{Chart, Curve, Mark, PALETTE};
    let mut chart = Chart::new(title, x, y);
    chart.curves = curves
        .into_iter()
        .zip([PALETTE[0], PALETTE[3]].into_iter().cycle())
        .map(|((label, points), color)| Curve::new(label, points, Mark::Line, color))
        .collect();
    chart.save_png(path)
}

impl Model {
    fn name(&self) -> &'static str {
        match self {
            Model::Maugis { .. } => "maugis",
            Model::Jkr => "jkr",
            Model::Dmt => "dmt",
            Model::Greenwood { .. } => "greenwood",
            Model::Hertz { .. } => "hertz",
            Model::Layer { .. } => "layer",
            Model::Wavy { .. } => "wavy",
            Model::Area { .. } => "area",
            Model::Viscoelastic { .. } => "viscoelastic",
            Model::Sticky { .. } => "sticky",
        }
    }
}

impl TheoryArgs {
    /// Points on the curve.
    fn points(&self) -> usize {
        self.points.unwrap_or(200)
    }
}

/// The bytes a point of a curve takes at most: its numbers, its line of CSV and its point on a
/// plot.
const POINT_BYTES: f64 = 256.0;

pub fn theory(a: TheoryArgs) -> Result<()> {
    check_flags(&a)?;
    if let Model::Greenwood {
        tabor,
        max_approach,
        from,
        resolution,
        ring_width,
    } = a.model
    {
        return greenwood(&a, tabor, max_approach, from, resolution, ring_width);
    }
    match a.model {
        Model::Hertz {
            radius,
            modulus,
            max_approach,
        } => return hertz(&a, radius, modulus, max_approach),
        Model::Layer {
            radius,
            modulus,
            thickness,
            poisson,
            layer_base,
            substrate_modulus,
            substrate_poisson,
            max_approach,
            work_of_adhesion,
        } => {
            let sphere = layer_of(
                (radius, modulus, thickness, poisson),
                layer_base,
                (substrate_modulus, substrate_poisson),
            )?;
            return layer(&a, &sphere, max_approach, work_of_adhesion);
        }
        Model::Area { k, max_pressure } => return area(&a, k, max_pressure),
        Model::Viscoelastic {
            radius,
            modulus,
            ref maxwell_moduli,
            ref maxwell_times,
            rate,
            rise_time,
            load,
            duration,
        } => {
            if !(radius.is_finite() && radius > 0.0) {
                bail!("--radius must be finite and > 0, got {radius}");
            }
            let solid =
                theory::viscoelastic::Maxwell::new(modulus, maxwell_moduli, maxwell_times).map_err(|e| {
                    anyhow::anyhow!("--{} {}, got {}", e.name.replace('_', "-"), e.reason, e.value)
                })?;
            let positive = |name: &str, v: f64| {
                if v.is_finite() && v > 0.0 {
                    Ok(v)
                } else {
                    Err(anyhow::anyhow!("{name} must be finite and > 0, got {v}"))
                }
            };
            let history = match (rate, rise_time, load) {
                (Some(rate), Some(rise), None) => History::Rate {
                    rate: positive("--rate", rate)?,
                    rise: positive("--rise-time", rise)?,
                },
                (None, None, Some(load)) => {
                    let slowest = solid
                        .retardation()
                        .iter()
                        .map(|&(_, lambda)| lambda)
                        .fold(0.0, f64::max);
                    History::Load {
                        load: positive("--load", load)?,
                        duration: positive("--duration", duration.unwrap_or(10.0 * slowest))?,
                    }
                }
                _ => bail!("give --rate with --rise-time, or --load"),
            };
            return viscoelastic(&a, radius, &solid, history);
        }
        Model::Wavy {
            amplitude,
            wavelength,
            modulus,
            work_of_adhesion,
        } => {
            let wave = theory::wavy::Wave {
                amplitude,
                wavelength,
                e_star: modulus,
                work_of_adhesion,
            };
            return wavy(&a, &wave);
        }
        Model::Sticky {
            work_of_adhesion,
            modulus,
            rms_height,
            hurst,
            long_wavelength,
            rolloff_wavelength,
            short_wavelength,
        } => {
            return sticky_of(
                &a,
                [
                    work_of_adhesion,
                    modulus,
                    rms_height,
                    long_wavelength,
                    short_wavelength,
                ],
                hurst,
                rolloff_wavelength,
            );
        }
        _ => {}
    }
    let (lambda, tabor) = match a.model {
        Model::Maugis {
            lambda: Some(l),
            tabor: None,
        } => (l, None),
        Model::Maugis {
            lambda: None,
            tabor: Some(mu),
        } => (theory::maugis_parameter_of_tabor(mu), Some(mu)),
        Model::Maugis { .. } => bail!("give exactly one of --lambda or --tabor"),
        Model::Jkr => (1e7, None),
        Model::Dmt => (1e-7, None),
        Model::Greenwood { .. }
        | Model::Hertz { .. }
        | Model::Layer { .. }
        | Model::Area { .. }
        | Model::Sticky { .. }
        | Model::Viscoelastic { .. }
        | Model::Wavy { .. } => {
            unreachable!("handled above")
        }
    };
    maugis(&a, lambda, tabor)
}

/// Refuses the shared flags a model does not use, rather than ignore them.
fn check_flags(a: &TheoryArgs) -> Result<()> {
    let curve = !matches!(a.model, Model::Sticky { .. });
    let sampled = curve && !matches!(a.model, Model::Greenwood { .. });
    let radius = matches!(a.model, Model::Maugis { .. } | Model::Jkr | Model::Dmt);
    let summarised = !matches!(
        a.model,
        Model::Hertz { .. } | Model::Area { .. } | Model::Sticky { .. } | Model::Viscoelastic { .. }
    );
    for (given, applies, flag) in [
        (a.summary, summarised, "--summary"),
        (a.points.is_some(), sampled, "--points"),
        (a.max_radius.is_some(), radius, "--max-radius"),
        (a.plot.is_some(), curve, "--plot"),
    ] {
        if given && !applies {
            bail!("{flag} does not apply to `theory {}`", a.model.name());
        }
    }
    if a.summary && (a.plot.is_some() || a.points.is_some() || a.max_radius.is_some()) {
        bail!("--plot, --points and --max-radius shape the curve; --summary prints no curve");
    }
    if a.json && !a.summary && curve {
        bail!("--json formats the summary: add --summary");
    }
    if a.points() < 2 {
        bail!("--points must be at least 2");
    }
    // A curve is held (and plotted) whole: its points are bounded by memory before any is made.
    case::memory::check(
        &format!("a curve of {} points", a.points()),
        a.points() as f64 * POINT_BYTES,
    )?;
    Ok(())
}

/// Stickiness from plain numbers: `[w0 J/m^2, E* Pa, Rq m, long m, short m]`, the Hurst
/// exponent and the roll-off [m] (default: the long wavelength).
fn sticky_of(a: &TheoryArgs, numbers: [f64; 5], hurst: f64, rolloff_wavelength: Option<f64>) -> Result<()> {
    use std::f64::consts::PI;
    let [w0, e, rq, long, short] = numbers;
    let rolloff = rolloff_wavelength.unwrap_or(long);
    let all = [w0, e, rq, long, rolloff, short];
    if all.iter().any(|v| !(v.is_finite() && *v > 0.0))
        || !(short < rolloff && rolloff <= long)
        || !(hurst > 0.0 && hurst < 1.0)
    {
        bail!("need positive finite inputs, short < roll-off <= long wavelength and 0 < H < 1");
    }
    let spectrum = theory::rough::SelfAffineSpectrum {
        hurst,
        q_long: 2.0 * PI / long,
        q_rolloff: 2.0 * PI / rolloff,
        q_short: 2.0 * PI / short,
        rms_height: rq,
    };
    sticky(a, w0, e, long, &spectrum)
}

/// The Maugis-Dugdale sphere at `lambda` (of the Tabor parameter `tabor`, if given): its
/// summary or its curve.
fn maugis(a: &TheoryArgs, lambda: f64, tabor: Option<f64>) -> Result<()> {
    if !(lambda.is_finite() && lambda > 0.0) {
        bail!("the Maugis parameter must be finite and > 0, got {lambda}");
    }
    let model = MaugisDugdale::new(lambda);
    let mut out = open(a)?;
    if a.summary {
        let (lc, dc, fold) = (
            model.pull_off_load_control(),
            model.pull_off_displacement_control(),
            model.has_fold(),
        );
        if a.json {
            let v = json!({
                "model": "maugis_dugdale", "lambda": lambda, "tabor_parameter": tabor,
                "units": "pull-off forces in pi R w0",
                "pull_off_load_control": lc, "pull_off_displacement_control": dc,
                "displacement_control_fold": fold,
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "Maugis-Dugdale, lambda = {lambda:.6}")?;
            writeln!(out, "pull-off under load control          {lc:.6} pi R w0")?;
            let note = if fold {
                ""
            } else {
                " (no fold below lambda ~0.94: separation is continuous, the load-control value)"
            };
            writeln!(out, "pull-off under displacement control  {dc:.6} pi R w0{note}")?;
        }
        return Ok(());
    }
    writeln!(out, "m,contact_radius_A,load_P,approach_D")?;
    let max_radius = a.max_radius.unwrap_or(3.0);
    if !(max_radius.is_finite() && max_radius > 0.0) {
        bail!("--max-radius must be finite and > 0");
    }
    let curve = model.curve_to_radius(a.points(), max_radius);
    for p in &curve {
        writeln!(out, "{:e},{:e},{:e},{:e}", p.m, p.radius, p.load, p.approach)?;
    }
    if let Some(path) = &a.plot {
        let pts = curve.iter().map(|p| (p.approach, p.load)).collect();
        draw(
            path,
            &format!("Maugis-Dugdale, lambda = {lambda:.4}"),
            "approach D",
            "load P = W/(pi R w0)",
            pts,
        )?;
    }
    Ok(())
}
