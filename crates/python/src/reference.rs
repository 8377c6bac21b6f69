//! The `theory` crate's reference models for `roughcontact.theory`: arrays in, arrays out
//! (the package turns lists into numpy arrays and back into the caller's shape).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use theory::greenwood::{Greenwood, Mesh};
use theory::maugis::MaugisDugdale;
use theory::wavy::Wave;

fn positive(name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(PyValueError::new_err(format!(
            "{name} must be finite and > 0, got {v}"
        )))
    }
}

fn map(x: &[f64], f: impl Fn(f64) -> f64) -> Vec<f64> {
    x.iter().map(|&v| f(v)).collect()
}

#[pyfunction]
fn tabor_parameter(radius: f64, work_of_adhesion: f64, modulus: f64, z0: f64) -> PyResult<f64> {
    Ok(theory::tabor_parameter(
        positive("radius", radius)?,
        positive("work_of_adhesion", work_of_adhesion)?,
        positive("modulus", modulus)?,
        positive("z0", z0)?,
    ))
}

#[pyfunction]
fn hertz(approach: Vec<f64>, radius: f64, modulus: f64) -> PyResult<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let (r, e) = (positive("radius", radius)?, positive("modulus", modulus)?);
    let a = map(&approach, |d| (r * d.max(0.0)).sqrt());
    Ok((
        map(&approach, |d| theory::hertz::load_of_approach(d, r, e)),
        a.clone(),
        map(&a, |a| {
            if a > 0.0 {
                theory::hertz::pressure(0.0, a, r, e)
            } else {
                0.0
            }
        }),
    ))
}

#[pyfunction]
fn jkr(
    contact_radius: Vec<f64>,
    radius: f64,
    work_of_adhesion: f64,
    modulus: f64,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let (r, w, e) = (
        positive("radius", radius)?,
        positive("work_of_adhesion", work_of_adhesion)?,
        positive("modulus", modulus)?,
    );
    Ok((
        map(&contact_radius, |a| theory::jkr_dmt::jkr_load(a, r, w, e)),
        map(&contact_radius, |a| theory::jkr_dmt::jkr_approach(a, r, w, e)),
    ))
}

#[pyfunction]
fn jkr_pull_off(radius: f64, work_of_adhesion: f64) -> PyResult<(f64, f64)> {
    let (r, w) = (
        positive("radius", radius)?,
        positive("work_of_adhesion", work_of_adhesion)?,
    );
    Ok((
        theory::jkr_dmt::jkr_pull_off_load_control(r, w),
        theory::jkr_dmt::jkr_pull_off_displacement_control(r, w),
    ))
}

#[pyfunction]
fn dmt(
    contact_radius: Vec<f64>,
    radius: f64,
    work_of_adhesion: f64,
    modulus: f64,
) -> PyResult<(Vec<f64>, f64)> {
    let (r, w, e) = (
        positive("radius", radius)?,
        positive("work_of_adhesion", work_of_adhesion)?,
        positive("modulus", modulus)?,
    );
    Ok((
        map(&contact_radius, |a| theory::jkr_dmt::dmt_load(a, r, w, e)),
        theory::jkr_dmt::dmt_pull_off(r, w),
    ))
}

/// Maugis-Dugdale at Tabor parameter `tabor` (lambda = 1.157 mu): contact radius A, load P,
/// approach D in Maugis' units, and the pull-offs.
#[pyfunction]
fn maugis_dugdale<'py>(
    py: Python<'py>,
    tabor: f64,
    points: usize,
    max_radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let model = MaugisDugdale::new(theory::maugis_parameter_of_tabor(positive("tabor", tabor)?));
    if points < 2 {
        return Err(PyValueError::new_err(format!(
            "points must be at least 2, got {points}"
        )));
    }
    let curve = model.curve_to_radius(points, positive("max_radius", max_radius)?);
    let d = PyDict::new(py);
    d.set_item("lambda", model.lambda)?;
    d.set_item("radius", curve.iter().map(|p| p.radius).collect::<Vec<_>>())?;
    d.set_item("load", curve.iter().map(|p| p.load).collect::<Vec<_>>())?;
    d.set_item("approach", curve.iter().map(|p| p.approach).collect::<Vec<_>>())?;
    d.set_item("pull_off_load_control", model.pull_off_load_control())?;
    d.set_item(
        "pull_off_displacement_control",
        model.pull_off_displacement_control(),
    )?;
    Ok(d)
}

/// Greenwood's Lennard-Jones sphere traced by its central separation.
#[pyfunction]
fn greenwood<'py>(
    py: Python<'py>,
    tabor: f64,
    max_approach: f64,
    start: f64,
    resolution: f64,
    ring_width: f64,
) -> PyResult<Bound<'py, PyDict>> {
    positive("tabor", tabor)?;
    if !(start > 1.0 && resolution > 0.0 && ring_width > 0.0 && ring_width < 1.0 && max_approach.is_finite())
    {
        return Err(PyValueError::new_err(
            "need start > 1, resolution > 0, 0 < ring_width < 1 and a finite max_approach",
        ));
    }
    let mesh = Mesh {
        spacing: ring_width,
        ..Mesh::default()
    };
    let c = py
        .detach(|| Greenwood::new(tabor, mesh).curve(start, max_approach, resolution))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    let column = |f: fn(&theory::greenwood::Point) -> f64| c.points.iter().map(f).collect::<Vec<_>>();
    d.set_item("central_separation", column(|p| p.central_separation))?;
    d.set_item("approach", column(|p| p.approach))?;
    d.set_item("load", column(|p| p.load))?;
    d.set_item("contact_radius", column(|p| p.contact_radius))?;
    d.set_item("jump_in", c.jump_in)?;
    d.set_item("jump_out", c.jump_out)?;
    d.set_item("pull_off_load_control", c.pull_off_load_control)?;
    d.set_item("pull_off_displacement_control", c.pull_off_displacement_control)?;
    Ok(d)
}

#[pyfunction]
fn persson_area(reduced_pressure: Vec<f64>) -> Vec<f64> {
    map(&reduced_pressure, theory::rough::persson_area)
}

#[pyfunction]
fn muser_area(reduced_pressure: Vec<f64>, k: f64) -> PyResult<Vec<f64>> {
    let k = positive("k", k)?;
    Ok(map(&reduced_pressure, |p| theory::rough::muser_area(p, k)))
}

#[pyfunction]
fn johnson_parameter(
    work_of_adhesion: f64,
    modulus: f64,
    rms_height: f64,
    q0: f64,
    q1: f64,
    hurst: f64,
) -> PyResult<f64> {
    Ok(theory::rough::johnson_parameter(
        positive("work_of_adhesion", work_of_adhesion)?,
        positive("modulus", modulus)?,
        positive("rms_height", rms_height)?,
        positive("q0", q0)?,
        positive("q1", q1)?,
        positive("hurst", hurst)?,
    ))
}

#[pyfunction]
fn ciavarella(
    rms_height: f64,
    modulus: f64,
    longest_wavelength: f64,
    work_of_adhesion: f64,
) -> PyResult<(f64, bool)> {
    let args = (
        positive("rms_height", rms_height)?,
        positive("modulus", modulus)?,
        positive("longest_wavelength", longest_wavelength)?,
        positive("work_of_adhesion", work_of_adhesion)?,
    );
    Ok((
        theory::rough::ciavarella_variable(args.0, args.1, args.2, args.3),
        theory::rough::ciavarella_sticky(args.0, args.1, args.2, args.3),
    ))
}

/// Westergaard's and Johnson's wave: mean pressures at the strips' half-widths, and the
/// wave's characteristic numbers.
#[pyfunction]
fn wave<'py>(
    py: Python<'py>,
    half_width: Vec<f64>,
    amplitude: f64,
    wavelength: f64,
    modulus: f64,
    work_of_adhesion: f64,
) -> PyResult<Bound<'py, PyDict>> {
    if !(work_of_adhesion.is_finite() && work_of_adhesion >= 0.0) {
        return Err(PyValueError::new_err(format!(
            "work_of_adhesion must be finite and >= 0, got {work_of_adhesion}"
        )));
    }
    let w = Wave {
        amplitude: positive("amplitude", amplitude)?,
        wavelength: positive("wavelength", wavelength)?,
        e_star: positive("modulus", modulus)?,
        work_of_adhesion,
    };
    if let Some(a) = half_width
        .iter()
        .find(|a| !(**a >= 0.0 && **a < w.wavelength / 2.0))
    {
        return Err(PyValueError::new_err(format!(
            "a half-width must lie in [0, wavelength/2), got {a}"
        )));
    }
    let d = PyDict::new(py);
    d.set_item("westergaard", map(&half_width, |a| w.westergaard_pressure(a)))?;
    d.set_item("jkr", map(&half_width, |a| w.jkr_pressure(a)))?;
    d.set_item("full_contact_pressure", w.full_contact_pressure())?;
    d.set_item("johnson_alpha", w.johnson_alpha())?;
    d.set_item("crest_radius", w.crest_radius())?;
    if work_of_adhesion > 0.0 {
        d.set_item("jkr_pull_off", w.jkr_pull_off())?;
        d.set_item("jkr_snap_to_full_contact", w.jkr_snap_to_full_contact())?;
    }
    Ok(d)
}

/// The layer `(thickness [m], poisson, base, substrate modulus [Pa], substrate poisson)`,
/// checked, with the error naming its keyword.
fn layer_of(
    thickness: f64,
    poisson: f64,
    layer_base: &str,
    substrate: (Option<f64>, Option<f64>),
) -> PyResult<elastic::Layer> {
    let base = match (layer_base, substrate) {
        ("bonded", (None, None)) => elastic::Base::Bonded,
        ("frictionless", (None, None)) => elastic::Base::Frictionless,
        ("elastic", (Some(e_star), Some(poisson))) => elastic::Base::Substrate { e_star, poisson },
        ("elastic", _) => {
            return Err(PyValueError::new_err(
                "layer_base 'elastic' needs substrate_modulus [Pa] and substrate_poisson",
            ));
        }
        ("bonded" | "frictionless", _) => {
            return Err(PyValueError::new_err(
                "substrate_modulus and substrate_poisson are a coating's: give layer_base='elastic'",
            ));
        }
        (other, _) => {
            return Err(PyValueError::new_err(format!(
                "layer_base must be 'bonded', 'frictionless' or 'elastic', got {other:?}"
            )));
        }
    };
    elastic::Layer::new(thickness, poisson, base).map_err(|e| match e {
        elastic::ElasticError::InvalidParameter { name, value, reason } => {
            PyValueError::new_err(format!("{name} {reason}, got {value}"))
        }
        other => PyValueError::new_err(other.to_string()),
    })
}

/// The exact sphere on `layer` of plane-strain modulus `e` \[Pa\].
fn exact(layer: &elastic::Layer, e: f64) -> theory::layer::LayerContact<impl Fn(f64) -> f64 + '_> {
    let h = layer.thickness;
    theory::layer::LayerContact::new(h, e, move |x| layer.compliance_ratio(x / h, e))
}

/// The exact frictionless sphere on a layer at the contact radii: loads [N] and approaches
/// [m] (JKR's on the layer with a work of adhesion, Hertz's without).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn layer(
    py: Python<'_>,
    contact_radius: Vec<f64>,
    radius: f64,
    modulus: f64,
    thickness: f64,
    poisson: f64,
    layer_base: &str,
    substrate_modulus: Option<f64>,
    substrate_poisson: Option<f64>,
    work_of_adhesion: f64,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let (r, e) = (positive("radius", radius)?, positive("modulus", modulus)?);
    if !(work_of_adhesion.is_finite() && work_of_adhesion >= 0.0) {
        return Err(PyValueError::new_err(format!(
            "work_of_adhesion must be finite and >= 0, got {work_of_adhesion}"
        )));
    }
    if let Some(a) = contact_radius.iter().find(|a| !(a.is_finite() && **a > 0.0)) {
        return Err(PyValueError::new_err(format!(
            "a contact radius must be finite and > 0, got {a}"
        )));
    }
    let layer = layer_of(
        thickness,
        poisson,
        layer_base,
        (substrate_modulus, substrate_poisson),
    )?;
    let body = exact(&layer, e);
    let points: Vec<_> = py.detach(|| {
        contact_radius
            .iter()
            .map(|&a| body.sphere(a, r, work_of_adhesion))
            .collect()
    });
    Ok((
        points.iter().map(|p| p.load).collect(),
        points.iter().map(|p| p.approach).collect(),
    ))
}

/// JKR's pull-off on a layer: load [N], contact radius [m] and approach [m] at it.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn layer_pull_off(
    py: Python<'_>,
    radius: f64,
    work_of_adhesion: f64,
    modulus: f64,
    thickness: f64,
    poisson: f64,
    layer_base: &str,
    substrate_modulus: Option<f64>,
    substrate_poisson: Option<f64>,
) -> PyResult<(f64, f64, f64)> {
    let (r, w, e) = (
        positive("radius", radius)?,
        positive("work_of_adhesion", work_of_adhesion)?,
        positive("modulus", modulus)?,
    );
    let layer = layer_of(
        thickness,
        poisson,
        layer_base,
        (substrate_modulus, substrate_poisson),
    )?;
    let off = py.detach(|| exact(&layer, e).pull_off(r, w));
    Ok((off.load, off.radius, off.approach))
}

/// A generalized Maxwell solid from its relaxed modulus \[Pa\] and branches.
fn maxwell(modulus: f64, moduli: &[f64], times: &[f64]) -> PyResult<theory::viscoelastic::Maxwell> {
    theory::viscoelastic::Maxwell::new(modulus, moduli, times)
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// A sphere on a generalized Maxwell solid pressed in at `rate` until `rise_time` and drawn
/// back: contact radii [m] and loads [N] at the times [s] (Lee & Radok, then Ting).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn viscoelastic_indentation(
    time: Vec<f64>,
    radius: f64,
    modulus: f64,
    maxwell_moduli: Vec<f64>,
    maxwell_times: Vec<f64>,
    rate: f64,
    rise_time: f64,
) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let solid = maxwell(modulus, &maxwell_moduli, &maxwell_times)?;
    let (r, v, rise) = (
        positive("radius", radius)?,
        positive("rate", rate)?,
        positive("rise_time", rise_time)?,
    );
    if let Some(t) = time.iter().find(|t| !(t.is_finite() && **t >= 0.0)) {
        return Err(PyValueError::new_err(format!(
            "a time must be finite and >= 0 s, got {t}"
        )));
    }
    let points: Vec<(f64, f64)> = time
        .iter()
        .map(|&t| theory::viscoelastic::triangle(&solid, t, r, v, rise))
        .collect();
    Ok((
        points.iter().map(|p| p.0).collect(),
        points.iter().map(|p| p.1).collect(),
    ))
}

/// Lee & Radok's creep of a sphere under a load [N] put on at time 0: contact radii [m] at the
/// times [s].
#[pyfunction]
fn viscoelastic_creep(
    time: Vec<f64>,
    radius: f64,
    modulus: f64,
    maxwell_moduli: Vec<f64>,
    maxwell_times: Vec<f64>,
    load: f64,
) -> PyResult<Vec<f64>> {
    let solid = maxwell(modulus, &maxwell_moduli, &maxwell_times)?;
    let (r, p) = (positive("radius", radius)?, positive("load", load)?);
    if let Some(t) = time.iter().find(|t| !(t.is_finite() && **t >= 0.0)) {
        return Err(PyValueError::new_err(format!(
            "a time must be finite and >= 0 s, got {t}"
        )));
    }
    Ok(map(&time, |t| {
        theory::viscoelastic::creep_radius(&solid, t, r, p)
    }))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(viscoelastic_indentation, m)?)?;
    m.add_function(wrap_pyfunction!(viscoelastic_creep, m)?)?;
    m.add_function(wrap_pyfunction!(layer, m)?)?;
    m.add_function(wrap_pyfunction!(layer_pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(tabor_parameter, m)?)?;
    m.add_function(wrap_pyfunction!(hertz, m)?)?;
    m.add_function(wrap_pyfunction!(jkr, m)?)?;
    m.add_function(wrap_pyfunction!(jkr_pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(dmt, m)?)?;
    m.add_function(wrap_pyfunction!(maugis_dugdale, m)?)?;
    m.add_function(wrap_pyfunction!(greenwood, m)?)?;
    m.add_function(wrap_pyfunction!(persson_area, m)?)?;
    m.add_function(wrap_pyfunction!(muser_area, m)?)?;
    m.add_function(wrap_pyfunction!(johnson_parameter, m)?)?;
    m.add_function(wrap_pyfunction!(ciavarella, m)?)?;
    m.add_function(wrap_pyfunction!(wave, m)?)?;
    Ok(())
}
