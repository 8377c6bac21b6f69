//! A layer end to end: the flags reach the problem and the record; refusals name the flag.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("roughcontact-layer-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// A smooth sphere (R = 1 mm, E* = 1 MPa) pressed 10 um on a 64^2 free grid, with `extra`.
fn sphere(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "solve",
        "--sphere-radius",
        "1e-3",
        "--n",
        "64",
        "--length",
        "4e-4",
        "--modulus",
        "1e6",
        "--approach",
        "1e-5",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn a_sphere_on_a_film_is_stiffer_than_on_the_half_space_and_the_record_says_why() {
    let d = dir("film");
    let half = sphere(&d.join("half"), &[]);
    assert!(half.status.success(), "{}", String::from_utf8_lossy(&half.stderr));
    let film = sphere(
        &d.join("film"),
        &[
            "--thickness",
            "2e-4",
            "--poisson",
            "0.45",
            "--layer-base",
            "frictionless",
        ],
    );
    assert!(film.status.success(), "{}", String::from_utf8_lossy(&film.stderr));
    let (half, film) = (summary(&d.join("half")), summary(&d.join("film")));
    let load = |s: &serde_json::Value| s["load"].as_f64().unwrap();
    // chi = sqrt(R delta) / h = 0.5: Dimitriadis gives 1.54 for the sliding layer.
    let ratio = load(&film) / load(&half);
    assert!(ratio > 1.4 && ratio < 1.7, "{ratio}");
    assert_eq!(film["case"]["thickness"].as_f64(), Some(2e-4));
    assert_eq!(film["case"]["poisson"].as_f64(), Some(0.45));
    assert_eq!(film["case"]["layer_base"].as_str(), Some("frictionless"));
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn bad_layers_are_refused_by_name() {
    let d = dir("refused");
    for (extra, says) in [
        (&["--thickness", "0", "--poisson", "0.3"][..], "--thickness"),
        (&["--thickness", "-1e-6", "--poisson", "0.3"][..], "--thickness"),
        (&["--thickness", "nan", "--poisson", "0.3"][..], "--thickness"),
        (&["--thickness", "1e-4", "--poisson", "0.6"][..], "--poisson"),
        (&["--thickness", "1e-4", "--poisson", "-1"][..], "--poisson"),
        (&["--thickness", "1e-4"][..], "--poisson"),
        (&["--poisson", "0.3"][..], "--poisson"),
        (&["--layer-base", "bonded"][..], "--layer-base"),
        (
            &[
                "--thickness",
                "1e-4",
                "--poisson",
                "0.3",
                "--substrate-modulus",
                "1e9",
            ][..],
            "--substrate-modulus",
        ),
        (
            &[
                "--thickness",
                "1e-4",
                "--poisson",
                "0.3",
                "--layer-base",
                "elastic",
            ][..],
            "--substrate-modulus",
        ),
        (
            &[
                "--thickness",
                "1e-4",
                "--poisson",
                "0.3",
                "--layer-base",
                "elastic",
                "--substrate-modulus",
                "1e9",
            ][..],
            "--substrate-poisson",
        ),
        (
            &[
                "--thickness",
                "1e-4",
                "--poisson",
                "0.3",
                "--layer-base",
                "elastic",
                "--substrate-modulus",
                "1e9",
                "--substrate-poisson",
                "0.5",
            ][..],
            "--substrate-poisson must be below 0.5",
        ),
    ] {
        let o = sphere(&d.join("x"), extra);
        assert!(!o.status.success(), "{extra:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{extra:?}: {err}");
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn theory_layer_gives_the_exact_load_beside_dimitriadis_hertz_and_winkler() {
    let o = run(&[
        "theory",
        "layer",
        "--radius",
        "1e-3",
        "--modulus",
        "1e6",
        "--thickness",
        "2e-4",
        "--poisson",
        "0.5",
        "--max-approach",
        "1e-5",
        "--points",
        "3",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = String::from_utf8(o.stdout).unwrap();
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    let number = |k: usize| -> f64 { last[k].parse().unwrap() };
    // chi = 0.5 on an incompressible bonded layer: 1 + 1.133 chi + 1.283 chi^2 + 0.769 chi^3
    // - 0.0974 chi^4 times Hertz; no Winkler limit (no compressibility). The exact load lies
    // above the fit there (docs/validation.md).
    let (approach, chi, fit, hertz, exact) = (number(0), number(1), number(2), number(3), number(5));
    assert!(
        (approach / 1e-5 - 1.0).abs() < 1e-9 && (chi - 0.5).abs() < 1e-9,
        "{last:?}"
    );
    let poly = 1.0 + 1.133 * 0.5 + 1.283 * 0.25 + 0.769 * 0.125 - 0.0974 * 0.0625;
    assert!((fit / hertz / poly - 1.0).abs() < 1e-3, "{fit} {hertz}");
    assert_eq!(last[4], "");
    assert!(exact / fit > 1.05 && exact / fit < 1.15, "{exact} {fit}");
    let o = run(&[
        "theory",
        "layer",
        "--radius",
        "1e-3",
        "--modulus",
        "1e6",
        "--thickness",
        "-1",
        "--poisson",
        "0.3",
        "--max-approach",
        "1e-5",
    ]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--thickness must"));
}

#[test]
fn theory_layer_summary_is_jkr_pull_off_and_a_thick_layer_is_the_half_space() {
    let sphere = [
        "theory",
        "layer",
        "--radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--summary",
    ];
    let summary = |thickness: &str| {
        let film = ["--thickness", thickness, "--poisson", "0.45"];
        let o = run(&[&sphere[..], &film, &["--work-of-adhesion", "0.089", "--json"]].concat());
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let get = |k: &str| v[k].as_f64().unwrap();
        (get("pull_off_load"), get("half_space_pull_off_load"))
    };
    let (thick, half) = summary("7e-5");
    assert!((half / (-1.5 * std::f64::consts::PI * 1e-6 * 0.089) - 1.0).abs() < 1e-12);
    assert!((thick / half - 1.0).abs() < 1e-4, "{thick} {half}");
    // A film as thick as the contact radius pulls off harder.
    let (thin, _) = summary("6.8e-8");
    assert!(thin / half > 1.1, "{thin} {half}");
    let o = run(&[&sphere[..], &["--thickness", "1e-7", "--poisson", "0.3"]].concat());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--work-of-adhesion"));
}

#[test]
fn a_coating_on_a_rough_periodic_surface_lies_between_its_substrate_and_its_own_material() {
    // A stiff coating (E* 1 GPa) 2 um thick on a soft substrate (E* 0.1 GPa): the contact area
    // at a mean pressure lies between the half-spaces of either material.
    let d = dir("coating");
    let area = |name: &str, extra: &[&str]| {
        let out = d.join(name);
        let mut args = vec![
            "solve",
            "--rms-gradient",
            "0.5",
            "--n",
            "64",
            "--length",
            "1e-4",
            "--mean-pressure",
            "1e6",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        summary(&out)["contact_area_fraction"].as_f64().unwrap()
    };
    let stiff = area("stiff", &["--modulus", "1e9"]);
    let soft = area("soft", &["--modulus", "1e8"]);
    let coated = area(
        "coated",
        &[
            "--modulus",
            "1e9",
            "--thickness",
            "2e-6",
            "--poisson",
            "0.3",
            "--layer-base",
            "elastic",
            "--substrate-modulus",
            "1e8",
            "--substrate-poisson",
            "0.45",
        ],
    );
    assert!(stiff < coated && coated < soft, "{stiff} {coated} {soft}");
    std::fs::remove_dir_all(&d).ok();
}
