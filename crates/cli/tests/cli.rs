//! The binary end to end: files written, numbers reported, bad input refused.

use std::path::PathBuf;
use std::process::{Command, Output};

fn roughcontact(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("roughcontact-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `roughcontact sweep --example NAME --no-png --out OUT EXTRA...`.
fn sweep_example(name: &str, out: &str, extra: &[&str]) -> Output {
    roughcontact(&[&["sweep", "--example", name, "--no-png", "--out", out][..], extra].concat())
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn help_texts_name_their_units() {
    for cmd in ["generate", "info", "stats", "psd", "solve", "sweep", "theory"] {
        let o = roughcontact(&[cmd, "--help"]);
        assert!(o.status.success());
        insta::assert_snapshot!(format!("help_{cmd}"), stdout(&o));
    }
    let o = roughcontact(&["--help"]);
    insta::assert_snapshot!("help", stdout(&o));
}

fn sample(name: &str) -> String {
    format!(
        "{}/../../data/topography-samples/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn info_lists_a_files_channels_and_the_flags_choose_and_fill() {
    let o = roughcontact(&["info", &sample("di-3.di"), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let info: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let names: Vec<&str> = info["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["ZSensor", "AmplitudeError", "Phase", "Height"]);
    assert_eq!(info["reads_as"]["Ok"]["channel"], 0);
    // The channel by name, and a channel that holds no heights refused naming what it holds.
    let o = roughcontact(&["stats", &sample("di-3.di"), "--channel", "Height", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = roughcontact(&["stats", &sample("di-3.di"), "--channel", "Phase"]);
    assert!(
        !o.status.success() && stderr(&o).contains("'Phase' holds º, not heights"),
        "{}",
        stderr(&o)
    );
    // Unmeasured points: counted by info, refused by a calculation, filled on request.
    let o = roughcontact(&["info", &sample("opd-1.opd")]);
    assert!(
        stdout(&o).contains("116 of 307200 points not measured"),
        "{}",
        stdout(&o)
    );
    let o = roughcontact(&["stats", &sample("opd-1.opd")]);
    assert!(
        !o.status.success() && stderr(&o).contains("--fill-unmeasured"),
        "{}",
        stderr(&o)
    );
    let o = roughcontact(&["stats", &sample("opd-1.opd"), "--fill-unmeasured"]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A case file names the channel and the fill too.
    let d = dir("info");
    let case = d.join("case.toml");
    std::fs::write(
        &case,
        format!(
            "surface = \"{}\"\nchannel = \"ZSensor\"\nmodulus = 1e9\nmean_pressure = 1e6\n",
            sample("di-3.di")
        ),
    )
    .unwrap();
    let o = roughcontact(&[
        "solve",
        "--config",
        case.to_str().unwrap(),
        "--no-png",
        "--out",
        d.join("run").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn generate_writes_surface_sidecar_and_picture_and_stats_agree() {
    let d = dir("gen");
    let out = d.join("s.npy");
    let o = roughcontact(&[
        "generate",
        "--n",
        "256",
        "--length",
        "1e-4",
        "--hurst",
        "0.8",
        "--rolloff",
        "2.5e-5",
        "--cutoff",
        "1.6e-6",
        "--rms-height",
        "1e-6",
        "--seed",
        "3",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!((report["rms_height"].as_f64().unwrap() / 1e-6 - 1.0).abs() < 1e-12);
    for f in ["s.npy", "s.json", "s.png"] {
        assert!(d.join(f).metadata().unwrap().len() > 100, "{f}");
    }
    let sidecar: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    assert_eq!(sidecar["grid"]["nx"], 256);
    assert_eq!(sidecar["spec"]["seed"], 3);

    // `stats` re-reads the file and finds the same numbers.
    let o = roughcontact(&["stats", out.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let again: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    for key in [
        "rms_height",
        "rms_gradient",
        "rms_curvature",
        "hurst_fit",
        "skewness",
        "kurtosis",
    ] {
        let (a, b) = (report[key].as_f64().unwrap(), again[key].as_f64().unwrap());
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{key}: {a} vs {b}");
    }
    assert!((again["hurst_fit"].as_f64().unwrap() - 0.8).abs() < 0.05);

    // The table names its units.
    let o = roughcontact(&["stats", out.to_str().unwrap()]);
    let table = stdout(&o);
    assert!(
        table.contains("RMS height Rq") && table.contains("1/m"),
        "{table}"
    );

    // `psd` writes CSV and a plot.
    let o = roughcontact(&["psd", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(d.join("s_psd.csv")).unwrap();
    assert!(csv.starts_with("q_rad_per_m,psd_m4,std_err_m4,count\n"));
    assert!(csv.lines().count() > 10);
    assert!(d.join("s_psd.png").exists());
}

#[test]
fn the_same_seed_gives_the_same_file() {
    let d = dir("seed");
    let run = |name: &str, threads: &str| {
        let p = d.join(name);
        let o = roughcontact(&[
            "--threads",
            threads,
            "generate",
            "--n",
            "64",
            "--no-png",
            "-o",
            p.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(p).unwrap()
    };
    assert_eq!(run("a.npy", "1"), run("b.npy", "2"));
}

#[test]
fn bare_files_need_their_size_and_text_formats_read_back() {
    let d = dir("formats");
    let xyz = d.join("s.xyz");
    let o = roughcontact(&["generate", "--n", "32", "--no-png", "-o", xyz.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = roughcontact(&["stats", xyz.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!((v["length_x"].as_f64().unwrap() / 1e-4 - 1.0).abs() < 1e-12);

    let txt = d.join("bare.txt");
    std::fs::write(&txt, "0 1 2\n1 2 3\n2 3 4\n").unwrap();
    let o = roughcontact(&["stats", txt.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--length"), "{}", stderr(&o));
    let o = roughcontact(&["stats", txt.to_str().unwrap(), "--length", "3e-6"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn bad_input_is_refused_clearly() {
    let d = dir("bad");
    let out = d.join("x.npy");
    let out = out.to_str().unwrap();
    let run = d.join("run");
    let run = run.to_str().unwrap();
    let cases: [(&[&str], &str); 9] = [
        (
            &["generate", "--n", "64", "--hurst", "1.3", "-o", out],
            "Hurst exponent",
        ),
        (
            &["sweep", "--example", "hertz", "--steps", "0", "--out", run],
            "--steps must be at least 1",
        ),
        (
            &[
                "sweep",
                "--example",
                "jkr-sphere",
                "--range",
                "1e-9",
                "--out",
                run,
            ],
            "does not apply to the Lennard-Jones laws",
        ),
        (
            &["sweep", "--example", "hertz", "--tolerance", "10", "--out", run],
            "between 1e-13 (what f64 arithmetic resolves) and 0.1",
        ),
        (
            &[
                "sweep",
                "--example",
                "jkr-sphere",
                "--tolerance",
                "0.5",
                "--out",
                run,
            ],
            "at most 0.1 (of the law's range)",
        ),
        (
            &["generate", "--n", "64", "--cutoff", "1e-7", "-o", out],
            "two grid spacings",
        ),
        (
            &["generate", "--n", "64", "--rms-height", "-1", "-o", out],
            "rms_height",
        ),
        (&["generate", "--n", "64", "--length", "0", "-o", out], "length_x"),
        (
            &[
                "generate",
                "--n",
                "64",
                "--rms-height",
                "1e-6",
                "--rms-gradient",
                "1",
                "-o",
                out,
            ],
            "cannot be used with",
        ),
    ];
    for (args, needle) in cases {
        let o = roughcontact(args);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
    }
    // Issue #31's cases: sizes this machine cannot hold are refused before allocating, flags a
    // command does not use are refused, and every message names what is wrong.
    let bad = d.join("bad.toml");
    std::fs::write(&bad, "modulus = \"abc\"\n").unwrap();
    let bad = bad.to_str().unwrap();
    let sub = d.join("sub");
    std::fs::create_dir_all(&sub).unwrap();
    let sub = sub.to_str().unwrap();
    let noext = d.join("noext");
    let noext = noext.to_str().unwrap();
    let sphere = [
        "solve",
        "--modulus",
        "1e9",
        "--length",
        "1e-6",
        "--approach",
        "1e-9",
        "--out",
        run,
    ];
    let sticky = [
        "theory",
        "sticky",
        "--work-of-adhesion",
        "0.05",
        "--modulus",
        "1e6",
        "--rms-height",
        "1e-6",
        "--long-wavelength",
        "1e-4",
        "--short-wavelength",
        "1e-7",
    ];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "sweep",
                "--example",
                "jkr-sphere",
                "--max-step",
                "1e-20",
                "--out",
                run,
            ],
            "substeps (at most 100000)",
        ),
        (
            vec![
                "sweep",
                "--example",
                "jkr-sphere",
                "--steps",
                "100000000000",
                "--out",
                run,
            ],
            "GiB of memory; this machine has",
        ),
        (
            vec!["generate", "--n", "1000000", "-o", out],
            "a 1000000 x 1000000 surface needs about",
        ),
        (
            [&sphere[..], &["--sphere-radius", "1e-6", "--n", "200000"]].concat(),
            "a 200000 x 200000 solve needs about",
        ),
        (
            [&sphere[..], &["--sphere-radius", "-1e-6", "--n", "64"]].concat(),
            "invalid sphere_radius = -1e-6: must be finite and > 0 m",
        ),
        (
            [&sphere[..], &["--sphere-radius=-1e-6", "--n", "64"]].concat(),
            "invalid sphere_radius",
        ),
        (vec!["stats", sub], "is a directory, not a surface file"),
        (
            vec!["generate", "--n", "64", "-o", noext],
            "the file name has no extension, which names the format",
        ),
        (
            vec!["solve", "--config", bad],
            "bad.toml: `modulus` must be a number, got \"abc\" (a string)",
        ),
        (
            vec!["generate", "--n", "3", "-o", out],
            "a 3 x 3 grid is too coarse for the default cut-off wavelength",
        ),
        (
            [&sticky[..], &["--points", "10"]].concat(),
            "--points does not apply to `theory sticky`",
        ),
        (
            [&sticky[..], &["--plot", "p.png"]].concat(),
            "--plot does not apply to `theory sticky`",
        ),
        (
            [&sticky[..], &["--max-radius", "2"]].concat(),
            "--max-radius does not apply to `theory sticky`",
        ),
        (
            vec!["theory", "greenwood", "--tabor", "1", "--points", "5"],
            "--points does not apply to `theory greenwood`",
        ),
        (
            vec![
                "theory",
                "maugis",
                "--lambda",
                "1",
                "--summary",
                "--plot",
                "p.png",
            ],
            "--summary prints no curve",
        ),
        (
            vec!["theory", "area", "--summary"],
            "--summary does not apply to `theory area`",
        ),
    ];
    for (args, needle) in &cases {
        let o = roughcontact(args);
        assert!(!o.status.success(), "{args:?} should fail");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(
            o.status.code() == Some(1) || o.status.code() == Some(2),
            "{args:?}: {:?}",
            o.status
        );
    }
    assert!(!d.join("run").exists(), "refused runs leave no output directory");
    let inf = d.join("inf.txt");
    std::fs::write(&inf, "0 1\ninf 2\n").unwrap();
    let o = roughcontact(&["stats", inf.to_str().unwrap(), "--length", "1e-6"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("line 2"), "{}", stderr(&o));
    // NaN is an unmeasured point: counted and refused, or filled on request.
    let nan = d.join("nan.txt");
    std::fs::write(&nan, "0 1\nnan 2\n").unwrap();
    let o = roughcontact(&["stats", nan.to_str().unwrap(), "--length", "1e-6"]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("1 of 4 points are not measured"),
        "{}",
        stderr(&o)
    );
    // A roll-off longer than the box is legal but warned about.
    let o = roughcontact(&[
        "generate",
        "--n",
        "64",
        "--rolloff",
        "2e-4",
        "--no-png",
        "-o",
        out,
    ]);
    assert!(o.status.success());
    assert!(stderr(&o).contains("warning: roll-off"), "{}", stderr(&o));
}

#[test]
fn solve_writes_fields_and_summary_and_refuses_bad_cases() {
    let d = dir("solve");
    let surf = d.join("s.npy");
    let o = roughcontact(&["generate", "--n", "64", "--no-png", "-o", surf.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = d.join("run");
    let o = roughcontact(&[
        "solve",
        "--surface",
        surf.to_str().unwrap(),
        "--modulus",
        "25e6",
        "--mean-pressure",
        "5e5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["converged"], true);
    assert!((summary["mean_pressure"].as_f64().unwrap() / 5e5 - 1.0).abs() < 1e-12);
    assert!(summary["surface_hash"].as_str().unwrap().starts_with("fnv1a64:"));
    for key in [
        "load",
        "approach",
        "contact_area_fraction",
        "iterations",
        "residual",
        "wall_time_s",
    ] {
        assert!(summary[key].is_number(), "{key}");
    }
    for f in ["pressure.npy", "gap.npy", "displacement.npy", "pressure.png"] {
        assert!(out.join(f).exists(), "{f}");
    }
    // A case file and a flag that overrides it.
    let toml = d.join("case.toml");
    std::fs::write(
        &toml,
        format!(
            "surface = {:?}\nmodulus = 25e6\nmean_pressure = 1e5\n",
            surf.to_str().unwrap()
        ),
    )
    .unwrap();
    let o = roughcontact(&[
        "solve",
        "--config",
        toml.to_str().unwrap(),
        "--mean-pressure",
        "2e5",
        "--print-config",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("mean_pressure = 200000.0"), "{}", stdout(&o));
    // Bad cases fail before any work, naming the problem.
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "solve",
                "--surface",
                surf.to_str().unwrap(),
                "--mean-pressure",
                "1e5",
            ],
            "--modulus",
        ),
        (
            &["solve", "--surface", surf.to_str().unwrap(), "--modulus", "1e6"],
            "exactly one",
        ),
        (
            &[
                "solve",
                "--surface",
                surf.to_str().unwrap(),
                "--modulus",
                "1e6",
                "--load",
                "-1",
            ],
            "load",
        ),
        (
            &[
                "solve",
                "--surface",
                surf.to_str().unwrap(),
                "--modulus",
                "1e6",
                "--mean-pressure",
                "1e5",
                "--n",
                "32",
            ],
            "the surface file has",
        ),
    ];
    for (args, needle) in cases {
        let o = roughcontact(args);
        assert!(!o.status.success(), "{args:?}");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
    }
    // A solve cut short says so and exits non-zero unless told to keep going.
    let short = [
        "solve",
        "--surface",
        surf.to_str().unwrap(),
        "--modulus",
        "25e6",
        "--mean-pressure",
        "5e5",
        "--max-iterations",
        "2",
        "--out",
    ];
    let o = roughcontact(&[&short[..], &[d.join("short").to_str().unwrap()]].concat());
    assert!(!o.status.success());
    assert!(stderr(&o).contains("did not converge"), "{}", stderr(&o));
    let o = roughcontact(
        &[
            &short[..],
            &[d.join("short").to_str().unwrap(), "--keep-going", "--overwrite"],
        ]
        .concat(),
    );
    assert!(o.status.success());
}

#[test]
fn theory_curves_and_pull_offs() {
    let mut text = String::new();
    for mu in ["0.1", "0.2", "0.3", "1", "2", "3"] {
        let o = roughcontact(&["theory", "maugis", "--tabor", mu, "--summary"]);
        assert!(o.status.success(), "{}", stderr(&o));
        text += &format!("mu = {mu}\n{}", stdout(&o));
    }
    insta::assert_snapshot!("maugis_pull_offs", text);
    let o = roughcontact(&["theory", "jkr", "--summary", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!((v["pull_off_load_control"].as_f64().unwrap() + 1.5).abs() < 1e-6);
    assert!((v["pull_off_displacement_control"].as_f64().unwrap() + 5.0 / 6.0).abs() < 1e-6);
    let o = roughcontact(&["theory", "dmt", "--points", "50"]);
    let csv = stdout(&o);
    assert!(csv.starts_with("m,contact_radius_A,load_P,approach_D\n"));
    assert_eq!(csv.lines().count(), 51);
    let o = roughcontact(&["theory", "maugis", "--lambda", "-1"]);
    assert!(!o.status.success());
    // Greenwood's Lennard-Jones sphere: an S at mu = 2, its pull-offs in 2 pi R w0, a plot.
    let o = roughcontact(&["theory", "greenwood", "--tabor", "2", "--summary", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let lc = v["pull_off_load_control"].as_f64().unwrap();
    assert!(lc < -0.75 && lc > -0.85, "{lc}");
    assert!(v["pull_off_displacement_control"].as_f64().unwrap() > lc);
    assert!(v["jump_in_approach"].as_f64().unwrap() > v["jump_out_approach"].as_f64().unwrap());
    let d = dir("greenwood");
    let png = d.join("g.png");
    let o = roughcontact(&[
        "theory",
        "greenwood",
        "--tabor",
        "0.5",
        "--plot",
        png.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("central_separation,approach,load,contact_radius\n"));
    assert!(png.exists());
    let o = roughcontact(&["theory", "greenwood", "--tabor", "0"]);
    assert!(!o.status.success());
    // Rough-surface formulas: the challenge's spectrum at Rq = 0.76 um has an RMS gradient
    // near 1 and is not sticky on E* = 25 MPa with w0 = 50 mJ/m^2 by either criterion.
    let o = roughcontact(&[
        "theory",
        "sticky",
        "--work-of-adhesion",
        "0.05",
        "--modulus",
        "25e6",
        "--rms-height",
        "7.6e-7",
        "--long-wavelength",
        "1e-4",
        "--rolloff-wavelength",
        "2e-5",
        "--short-wavelength",
        "1e-7",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert!((v["rms_gradient"].as_f64().unwrap() - 1.0).abs() < 0.05);
    assert_eq!(v["ciavarella_sticky"], false);
    assert_eq!(v["persson_tosatti_sticky"], false);
    let o = roughcontact(&["theory", "area", "--points", "11", "--max-pressure", "0.01"]);
    let csv = stdout(&o);
    assert!(csv.starts_with("reduced_pressure,persson,muser\n"));
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        (last[2] / (2.0 * last[0]) - 1.0).abs() < 1e-3,
        "Muser's small-load slope is k"
    );
    let o = roughcontact(&[
        "theory",
        "hertz",
        "--radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--max-approach",
        "1e-9",
    ]);
    assert!(o.status.success());
    // The wave: p* = pi E* A / lambda, Johnson's alpha, and a narrow strip on the crest's
    // cylinder (Westergaard's p lambda -> pi E* a^2 / (4 R)).
    let wave = [
        "theory",
        "wavy",
        "--amplitude",
        "1e-8",
        "--wavelength",
        "1e-6",
        "--modulus",
        "1e9",
    ];
    let o = roughcontact(&[&wave[..], &["--work-of-adhesion", "0.05", "--summary", "--json"]].concat());
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let p_star = std::f64::consts::PI * 1e9 * 1e-8 / 1e-6;
    assert!((v["full_contact_pressure"].as_f64().unwrap() / p_star - 1.0).abs() < 1e-12);
    let alpha = (2.0 * 1e-6 * 0.05 / (std::f64::consts::PI.powi(2) * 1e9 * 1e-16)).sqrt();
    assert!((v["johnson_parameter"].as_f64().unwrap() / alpha - 1.0).abs() < 1e-12);
    assert!(v["jkr_pull_off_mean_pressure"].as_f64().unwrap() < 0.0);
    let o = roughcontact(&[&wave[..], &["--points", "1000"]].concat());
    let csv = stdout(&o);
    assert!(csv.starts_with("half_width_m,contact_fraction,westergaard_pressure_pa,jkr_pressure_pa\n"));
    let row: Vec<f64> = csv
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let r = v["crest_radius"].as_f64().unwrap();
    let cylinder = std::f64::consts::PI * 1e9 * row[0] * row[0] / (4.0 * r) / 1e-6;
    assert!((row[2] / cylinder - 1.0).abs() < 1e-4, "{row:?}");
    // Without adhesion JKR is Westergaard.
    assert_eq!(row[2], row[3]);
    let o = roughcontact(&[
        "theory",
        "wavy",
        "--amplitude",
        "-1",
        "--wavelength",
        "1",
        "--modulus",
        "1",
    ]);
    assert!(!o.status.success());
}

#[test]
fn theory_viscoelastic_creeps_and_unloads_between_the_relaxed_and_glassy_hertz() {
    let solid = [
        "theory",
        "viscoelastic",
        "--radius",
        "1e-3",
        "--modulus",
        "1e6",
        "--maxwell-moduli",
        "9e6",
        "--maxwell-times",
        "1",
    ];
    // The curve's rows of numbers, for the history `extra`.
    let rows = |extra: &[&str]| -> Vec<Vec<f64>> {
        let o = roughcontact(&[&solid[..], extra].concat());
        assert!(o.status.success(), "{}", stderr(&o));
        stdout(&o)
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect()
    };
    // A step load on E0 / E_inf = 10: from the glassy Hertz radius to the relaxed one,
    // 10^(1/3) wider.
    let creep = rows(&["--load", "1e-2", "--duration", "1e4", "--points", "3"]);
    let (first, last) = (&creep[0], &creep[2]);
    assert!((first[1] / first[4] - 1.0).abs() < 1e-12, "{first:?}");
    assert!((last[1] / last[3] - 1.0).abs() < 1e-12, "{last:?}");
    assert!((last[1] / first[1] - 10f64.cbrt()).abs() < 1e-9);
    // In at a rate and out: the load lies between the relaxed and glassy Hertz loads while
    // the contact grows, and the contact opens before the approach returns to zero.
    let cycle = rows(&["--rate", "1e-6", "--rise-time", "3", "--points", "5"]);
    let top = &cycle[2];
    assert!(top[3] > top[4] && top[3] < top[5], "{top:?}");
    assert_eq!((cycle[3][2], cycle[3][3]), (0.0, 0.0));
    for (extra, says) in [
        (
            &["--maxwell-times", "-1", "--load", "1"][..],
            "--maxwell-times values must be",
        ),
        (
            &["--maxwell-times", "1,2", "--load", "1"][..],
            "--maxwell-times must hold one time a branch modulus (1 given), got 2",
        ),
        (
            &["--maxwell-times", "1", "--rate", "-1", "--rise-time", "1"][..],
            "--rate must be",
        ),
    ] {
        let o = roughcontact(&[&solid[..8], extra].concat());
        assert!(
            !o.status.success() && stderr(&o).contains(says),
            "{extra:?}: {}",
            stderr(&o)
        );
    }
}

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn adhesive_solve_reports_both_pressures() {
    let d = dir("adh-solve");
    let out = d.join("run");
    let o = roughcontact(&[
        "solve",
        "--sphere-radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--n",
        "64",
        "--length",
        "2e-7",
        "--work-of-adhesion",
        "0.05",
        "--z0",
        "1e-9",
        "--approach",
        "-5e-10",
        "--no-png",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = json(&out.join("summary.json"));
    assert_eq!(s["converged"], true);
    assert_eq!(s["law"], "surface");
    assert!(s["load"].as_f64().unwrap() < 0.0, "adhesion pulls: {}", s["load"]);
    assert!(s["adhesive_load"].as_f64().unwrap() < 0.0);
    assert_eq!(s["iterations"]["kind"], "newton");
    assert!(s["iterations"]["krylov"].is_number() && s["method"] == "newton");
    for f in [
        "pressure",
        "compressive_pressure",
        "adhesive_pressure",
        "gap",
        "displacement",
    ] {
        assert!(out.join(format!("{f}.npy")).exists(), "{f}");
    }
    // A law without its parameters is refused before any work.
    let o = roughcontact(&[
        "solve",
        "--sphere-radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--n",
        "16",
        "--length",
        "2e-7",
        "--law",
        "exponential",
        "--work-of-adhesion",
        "0.05",
        "--approach",
        "0",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--range"), "{}", stderr(&o));
}

#[test]
fn sweep_example_writes_curve_and_summary_and_resumes() {
    let d = dir("sweep");
    let out = d.join("hertz");
    let o = roughcontact(&[
        "sweep",
        "--example",
        "hertz",
        "--n",
        "64",
        "--steps",
        "4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 9, "{csv}");
    assert!(
        lines[0]
            .starts_with("step,approach,load,mean_pressure,contact_area_fraction,attractive_area_fraction")
    );
    let s = json(&out.join("summary.json"));
    assert_eq!(s["converged"], true);
    // Without adhesion: no pull-off, no jumps, no hysteresis beyond round-off.
    assert!(s["pull_off_force"].is_null());
    assert!(s["jump_in_approach"].is_null());
    assert!(out.join("load_approach.png").exists());
    // Loading and unloading meet: the load at the turning point is Hertz's.
    let last: Vec<&str> = lines[5].split(',').collect();
    let (delta, load): (f64, f64) = (last[1].parse().unwrap(), last[2].parse().unwrap());
    let hertz = 4.0 / 3.0 * 1e9 * 1e-6f64.sqrt() * delta.powf(1.5);
    assert!((load / hertz - 1.0).abs() < 0.05, "{load} vs {hertz}");

    // Cut the file after three steps: state/ holds the last step's state, not the third's,
    // so resuming from it is refused.
    let kept: Vec<&str> = lines[..4].to_vec();
    std::fs::write(out.join("curve.csv"), kept.join("\n") + "\n").unwrap();
    let resume = |extra: &[&str]| {
        let mut a = vec![
            "sweep",
            "--example",
            "hertz",
            "--n",
            "64",
            "--steps",
            "4",
            "--out",
            out.to_str().unwrap(),
        ];
        a.extend(extra);
        roughcontact(&a)
    };
    let o = resume(&["--resume"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("curve.csv's last step (2)"), "{}", stderr(&o));
    // With every step's state kept, a cut file resumes from its own last step: the same curve.
    let o = resume(&["--save-states", "--overwrite"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("states/step-0008/gap.npy").exists());
    let csv = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    std::fs::write(out.join("curve.csv"), lines[..4].join("\n") + "\n").unwrap();
    let o = resume(&["--resume"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("resuming after 3 of 9 steps"),
        "{}",
        stderr(&o)
    );
    let resumed = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let column = |text: &str, i: usize| -> Vec<f64> {
        text.lines()
            .skip(1)
            .map(|l| l.split(',').nth(i).unwrap().parse().unwrap())
            .collect()
    };
    let (a, b) = (column(&csv, 2), column(&resumed, 2));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-6 * x.abs().max(1e-12), "{x} vs {y}");
    }
    // Resuming with other settings is refused.
    let o = roughcontact(&[
        "sweep",
        "--example",
        "hertz",
        "--n",
        "64",
        "--steps",
        "5",
        "--resume",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("different case"), "{}", stderr(&o));
}

#[test]
fn sweep_refuses_bad_paths_and_warns_about_coarse_grids() {
    let o = roughcontact(&[
        "sweep",
        "--sphere-radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--n",
        "16",
        "--length",
        "2e-7",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--from"), "{}", stderr(&o));
    let o = roughcontact(&["sweep", "--example", "challenge-small", "--print-config"]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("mean_pressures"));
    let d = dir("coarse");
    let o = sweep_example(
        "challenge-small",
        d.join("c").to_str().unwrap(),
        &["--n", "32", "--mean-pressures", "2.5e5"],
    );
    assert!(stderr(&o).contains("process-zone"), "{}", stderr(&o));
    let o = roughcontact(&[
        "sweep",
        "--example",
        "dmt-sphere",
        "--max-step",
        "0",
        "--out",
        d.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--max-step"), "{}", stderr(&o));
}

#[test]
fn long_sweep_steps_are_split_into_substeps_of_the_range() {
    // dmt-sphere's z0 is 1 nm: a 3 nm step takes two substeps first.
    let d = dir("substeps");
    let o = sweep_example("dmt-sphere", d.to_str().unwrap(), &["--approaches=-2e-9,1e-9"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("note: 2 substeps"), "{}", stderr(&o));
    assert_eq!(json(&d.join("summary.json"))["max_step"], 1e-9);
}

#[test]
fn auto_takes_newton_or_the_flow_for_the_surface_law_under_approach_control() {
    // The law soft (dmt-sphere, 0.05 times a cell's stiffness), between (2.5 times) and stiff
    // (jkr-sphere, 4.6 times): Newton at each; on cells four times coarser (18 times), where
    // each cell holds on or lets go alone, the flow.
    let d = dir("newton");
    for (name, extra) in [
        ("soft", vec!["--example", "dmt-sphere"]),
        (
            "middle",
            vec!["--example", "dmt-sphere", "--work-of-adhesion", "0.05"],
        ),
    ] {
        let out = d.join(name);
        let o = roughcontact(
            &[
                &["sweep"][..],
                &extra,
                &["--approaches=-2e-9", "--no-png", "--out", out.to_str().unwrap()],
            ]
            .concat(),
        );
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(json(&out.join("summary.json"))["method"], "newton", "{name}");
    }
    let o = sweep_example("jkr-sphere", d.to_str().unwrap(), &["--approaches=-4e-9,-3e-9"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = json(&d.join("summary.json"));
    assert_eq!(summary["method"], "newton");
    assert_eq!(summary["converged"], true);
    let coarse = d.join("coarse");
    let o = sweep_example(
        "jkr-sphere",
        coarse.to_str().unwrap(),
        &["--n", "32", "--approaches=-4e-9,-3e-9"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = json(&coarse.join("summary.json"));
    assert_eq!(summary["method"], "flow");
    assert_eq!(summary["converged"], true);
    // ... and not where the user chose.
    let o = sweep_example(
        "jkr-sphere",
        d.join("chosen").to_str().unwrap(),
        &["--approaches=-4e-9", "--solver", "dual-loop"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(json(&d.join("chosen/summary.json"))["method"], "dual-loop");
}

#[test]
fn a_bistable_unloading_step_settles() {
    // On the rough sphere, unloading from 1 to 1.5 nm apart leaves a few cells undecided
    // between contact and separation; Anderson mixing alone orbited there for 20000 outer
    // iterations. The stall detection hands over to damped relaxation, which settles.
    let d = dir("bistable");
    let o = sweep_example(
        "rough-sphere",
        d.join("r").to_str().unwrap(),
        &[
            "--approaches=-1e-9,-1.5e-9",
            "--solver",
            "accelerated",
            "--max-iterations",
            "2000",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(json(&d.join("r/summary.json"))["converged"], true);
}

#[test]
fn a_sweep_started_from_a_saved_state_continues_its_branch() {
    let d = dir("start-from");
    let case = [
        "sweep",
        "--example",
        "jkr-sphere",
        "--n",
        "32",
        "--law",
        "point",
        "--solver",
        "energy",
    ];
    let run = |extra: &[&str]| roughcontact(&[&case[..], extra].concat());
    let whole = d.join("whole");
    let o = run(&["--steps", "4", "--save-states", "--out", whole.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let loads = |out: &std::path::Path| -> Vec<(f64, f64)> {
        std::fs::read_to_string(out.join("curve.csv"))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[1].parse().unwrap(), f[2].parse().unwrap())
            })
            .collect()
    };
    let cycle = loads(&whole);
    assert_eq!(cycle.len(), 9);
    // The way back from the turning point (step 4), started from that step's saved state: the
    // same unloading branch, attached where a start from apart is not.
    let back: Vec<String> = cycle[5..].iter().map(|(a, _)| format!("{a:e}")).collect();
    let approaches = format!("--approaches={}", back.join(","));
    let turning = whole.join("states/step-0004");
    let resumed = d.join("resumed");
    let o = run(&[
        &approaches,
        "--start-from",
        turning.to_str().unwrap(),
        "--out",
        resumed.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("starting from"), "{}", stderr(&o));
    let apart = d.join("apart");
    let last = format!("--approaches={}", back[3]);
    let o = run(&[&last, "--out", apart.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let scale = cycle.iter().fold(0.0f64, |m, (_, l)| m.max(l.abs()));
    let (from_state, from_apart) = (loads(&resumed), loads(&apart));
    for (k, (a, l)) in cycle[5..].iter().enumerate() {
        assert_eq!(from_state[k].0, *a);
        assert!(
            (from_state[k].1 - l).abs() <= 1e-9 * scale,
            "{:?} vs {l}",
            from_state[k]
        );
    }
    // At the last approach (-5 nm) the unloading branch still holds on; approached from apart,
    // the sphere does not jump in there.
    assert!(
        (from_apart[0].1 - cycle[8].1).abs() > 0.5 * scale,
        "{from_apart:?} vs {cycle:?}"
    );
    // A sweep's own directory stands for its last state (step 8, at this approach: solved
    // again from it, the same load to the solve's tolerance); a directory with no state is
    // refused, naming what it needs.
    let from_dir = d.join("from-dir");
    let o = run(&[
        &last,
        "--start-from",
        whole.to_str().unwrap(),
        "--out",
        from_dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        (loads(&from_dir)[0].1 - cycle[8].1).abs() <= 1e-5 * scale,
        "{:?} vs {:?}",
        loads(&from_dir),
        cycle[8]
    );
    let o = run(&[
        &last,
        "--start-from",
        d.to_str().unwrap(),
        "--out",
        d.join("none").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("holds no saved state"), "{}", stderr(&o));
    let missing = d.join("missing");
    let o = run(&[
        &last,
        "--start-from",
        missing.to_str().unwrap(),
        "--out",
        d.join("none").to_str().unwrap(),
    ]);
    assert!(
        stderr(&o).contains(&format!("{} does not exist", missing.display())),
        "{}",
        stderr(&o)
    );
    // Another grid is refused ...
    let o = roughcontact(&[
        "sweep",
        "--example",
        "jkr-sphere",
        "--n",
        "64",
        &approaches,
        "--start-from",
        turning.to_str().unwrap(),
        "--out",
        d.join("other").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("holds a (32, 32) grid"), "{}", stderr(&o));
    // ... before anything is written.
    assert!(!d.join("other").exists());
}

#[test]
fn the_dmt_sphere_example_has_no_jumps() {
    // At mu = 0.1 the load-approach curve is single-valued (DMT side): loading and unloading
    // coincide, with no jump in or out. (The accelerated loop at its default tolerance, which
    // `auto` took here before, reported a jump in at -1.0 nm and out at -1.1 nm.)
    let d = dir("dmt");
    let o = sweep_example("dmt-sphere", d.to_str().unwrap(), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = json(&d.join("summary.json"));
    assert!(s["jump_in_approach"].is_null(), "{s}");
    assert!(s["jump_out_approach"].is_null(), "{s}");
    // Pull-off force times the range: the scale of the cycle's work.
    let scale = s["pull_off_force"].as_f64().unwrap().abs() * 1e-9;
    assert!(
        s["hysteresis_energy"].as_f64().unwrap().abs() < 1e-4 * scale,
        "{s}"
    );
}

#[test]
fn the_wavy_jkr_example_pulls_off_at_johnsons_pressure() {
    // Johnson's (1995) adhesive wave at alpha = 0.3, the crests at Tabor parameter 3: the
    // unloading branch holds on to its fold (-7 z0; the accelerated loop left it at -5 z0, its
    // pull-off 2 % short) and pulls off within 1 % of Johnson's JKR mean pressure.
    let d = dir("wavy");
    let o = sweep_example("wavy-jkr", d.to_str().unwrap(), &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = json(&d.join("summary.json"));
    assert_eq!(s["method"], "newton");
    assert_eq!(s["converged"], true);
    assert!((s["tabor_parameter"].as_f64().unwrap() - 3.0).abs() < 0.01, "{s}");
    let wave = &s["wave"];
    assert!(
        (wave["johnson_parameter"].as_f64().unwrap() - 0.3).abs() < 0.001,
        "{s}"
    );
    let ratio = wave["pull_off_mean_pressure"].as_f64().unwrap()
        / wave["jkr_pull_off_mean_pressure"].as_f64().unwrap();
    assert!((ratio - 1.0).abs() < 0.01, "{s}");
    assert!(
        (s["jump_out_approach"].as_f64().unwrap() + 7e-9).abs() < 1e-12,
        "{s}"
    );
    // A wave repeats: a free domain is refused, and so is a sphere with it.
    for (extra, needle) in [
        (&["--domain", "free"][..], "periodic"),
        (&["--sphere-radius", "1e-6"][..], "not both"),
    ] {
        let o = sweep_example("wavy-jkr", d.join("refused").to_str().unwrap(), extra);
        assert!(!o.status.success());
        assert!(stderr(&o).contains(needle), "{}", stderr(&o));
    }
}

#[test]
fn a_box_that_cuts_the_tail_says_how_much() {
    // jkr-sphere's box ends at a gap of 4.92 z0; the Lennard-Jones tail beyond it holds
    // -V(4.92 z0) / w0 = 3.8 % of w0 (an independent evaluation of the 9-3 energy at the
    // atomic separation g + z0: V/w0 = (z0/z)^8 / 3 - 4 (z0/z)^2 / 3).
    let d = dir("tail");
    let o = sweep_example("jkr-sphere", d.to_str().unwrap(), &["--approaches=-9e-9"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let edge: f64 = (100.0f64 - 100.0 / 128.0).powi(2) / 2000.0; // (half-box minus half a cell)^2 / 2R [z0]
    let z: f64 = 1.0 / (edge + 1.0);
    let share = 4.0 / 3.0 * z.powi(2) - z.powi(8) / 3.0;
    let text = format!("the law holds {:.1} % of w0", 100.0 * share);
    assert!(stderr(&o).contains(&text), "{text}: {}", stderr(&o));
}

#[test]
fn non_finite_values_are_refused_with_their_key() {
    let d = dir("non-finite");
    let base = [
        "solve",
        "--sphere-radius",
        "1e-6",
        "--length",
        "2e-7",
        "--n",
        "16",
        "--approach",
        "1e-9",
    ];
    for (extra, key) in [
        (
            vec!["--modulus", "1e9", "--z0", "1e-9", "--work-of-adhesion", "nan"],
            "--work-of-adhesion",
        ),
        (vec!["--modulus", "inf"], "--modulus"),
        (vec!["--modulus", "1e9", "--tolerance", "nan"], "--tolerance"),
    ] {
        let o = roughcontact(&[&base[..], &extra, &["--out", d.to_str().unwrap()]].concat());
        assert!(!o.status.success(), "{extra:?} was accepted");
        let e = stderr(&o);
        assert!(e.contains(key) && e.contains("finite"), "{extra:?}: {e}");
    }
    let case = d.join("case.toml");
    std::fs::write(&case, "modulus = 1e9\nwork_of_adhesion = 0.05\nz0 = nan\n").unwrap();
    let o = roughcontact(&[&base[..], &["--config", case.to_str().unwrap()]].concat());
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("`z0`") && e.contains("finite"), "{e}");
}

#[test]
fn auto_picks_the_librarys_method_for_every_built_in_example() {
    use ljadhesion::{AdhesionLaw, ExponentialLaw, LennardJones, NoAdhesion, SurfaceLaw};
    use solver::{Control, Method};
    let d = dir("auto-examples");
    for (name, extra) in [
        ("hertz", vec!["--n", "16", "--steps", "1"]),
        ("jkr-sphere", vec!["--n", "16", "--steps", "1"]),
        ("dmt-sphere", vec!["--n", "16", "--steps", "1"]),
        ("rough-sphere", vec!["--n", "32", "--steps", "1"]),
        ("challenge-small", vec!["--n", "32", "--mean-pressures", "1.25e5"]),
        ("wavy-jkr", vec!["--n", "64", "--steps", "1"]),
    ] {
        // The library's choice for the example's law and path, from its case file alone.
        let text = std::fs::read_to_string(format!("../runs/cases/{name}.toml")).unwrap();
        let table: toml::Table = toml::from_str(&text).unwrap();
        let number = |k: &str| table.get(k).and_then(|v| v.as_float());
        let law: Box<dyn AdhesionLaw> = match table.get("law").and_then(|v| v.as_str()) {
            None => Box::new(NoAdhesion),
            Some("surface") => Box::new(SurfaceLaw(
                LennardJones::new(number("work_of_adhesion").unwrap(), number("z0").unwrap()).unwrap(),
            )),
            Some("exponential") => Box::new(
                ExponentialLaw::new(number("work_of_adhesion").unwrap(), number("range").unwrap()).unwrap(),
            ),
            Some(other) => panic!("{name}: add the law {other} here"),
        };
        let control = if table.contains_key("mean_pressures") {
            Control::MeanPressure(1.0)
        } else {
            Control::Approach(0.0)
        };
        // The grid as run: the example's length over the `--n` given here.
        let n: f64 = extra[1].parse().unwrap();
        let length = number("length").unwrap();
        let domain = elastic::Domain {
            nx: n as usize,
            ny: n as usize,
            dx: length / n,
            dy: length / n,
            periodic: table.get("sphere_radius").is_none(),
        };
        let e_star = number("modulus").unwrap();
        let expected = law.work_of_adhesion().gt(&0.0).then(|| {
            Method::Auto
                .resolve(
                    law.as_ref(),
                    control,
                    &domain,
                    domain.cell_compliance(e_star),
                    &Default::default(),
                )
                .name()
        });
        // The command line's choice, as its summary records it.
        let out = d.join(name);
        let o = sweep_example(name, out.to_str().unwrap(), &extra);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let solver = json(&out.join("summary.json"))["method"].clone();
        assert_eq!(solver.as_str(), expected, "{name}");
    }
}

#[test]
fn output_into_a_closed_pipe_ends_quietly() {
    // `roughcontact theory maugis | head -0`: the reader is gone before the first line.
    let mut child = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(["theory", "maugis", "--lambda", "1"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the binary runs");
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    // No panic, no "Broken pipe" error: the end of a pipeline is not a failure.
    let err = stderr(&out);
    assert!(
        err.is_empty() && out.status.code() != Some(101),
        "{:?}: {err}",
        out.status
    );
}

#[test]
fn run_directories_are_locked_kept_apart_and_resumed_wherever_they_are() {
    let d = dir("rundir");
    let out = d.join("hertz");
    // A 32^2 Hertz sweep of `steps` steps each way into `out`.
    let o = |out: &str, steps: &str, extra: &[&str]| {
        sweep_example(
            "hertz",
            out,
            &[&["--n", "32", "--steps", steps][..], extra].concat(),
        )
    };
    let first = o(out.to_str().unwrap(), "3", &["--save-states"]);
    assert!(first.status.success(), "{}", stderr(&first));
    // Another run into it is refused, and nothing there changes.
    let curve = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let again = o(out.to_str().unwrap(), "3", &[]);
    assert!(!again.status.success());
    assert!(
        stderr(&again).contains("already holds a run"),
        "{}",
        stderr(&again)
    );
    assert_eq!(std::fs::read_to_string(out.join("curve.csv")).unwrap(), curve);
    // A solve has its own default directory, so it never mixes its files into a sweep's.
    let solve = roughcontact(&[
        "solve",
        "--sphere-radius",
        "1e-6",
        "--modulus",
        "1e9",
        "--length",
        "1e-6",
        "--n",
        "32",
        "--approach",
        "1e-9",
        "--no-png",
        "--print-config",
    ]);
    assert!(
        stdout(&solve).contains("out = \"run/solve\""),
        "{}",
        stdout(&solve)
    );
    // The output path is not part of the case: a resume through another spelling of it, or
    // after the directory moved, is the same case.
    let moved = d.join("moved");
    std::fs::rename(&out, &moved).unwrap();
    let spelt = format!("{}/./", moved.display());
    let resumed = o(&spelt, "3", &["--save-states", "--resume"]);
    assert!(resumed.status.success(), "{}", stderr(&resumed));
    assert!(
        stderr(&resumed).contains("resuming after 7 of 7 steps"),
        "{}",
        stderr(&resumed)
    );
    // --overwrite replaces the run's files and leaves other files alone.
    std::fs::write(moved.join("notes.txt"), "mine").unwrap();
    let replaced = o(moved.to_str().unwrap(), "2", &["--overwrite"]);
    assert!(replaced.status.success(), "{}", stderr(&replaced));
    assert!(!moved.join("states").exists());
    assert_eq!(std::fs::read_to_string(moved.join("notes.txt")).unwrap(), "mine");
    assert_eq!(
        std::fs::read_to_string(moved.join("curve.csv"))
            .unwrap()
            .lines()
            .count(),
        1 + 5
    );
}

#[test]
fn two_sweeps_into_one_directory_one_is_refused() {
    let d = dir("lock");
    let out = d.join("busy");
    let mut first = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args([
            "sweep",
            "--example",
            "jkr-sphere",
            "--no-png",
            "--out",
            out.to_str().unwrap(),
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // The first holds its directory once it has written its case.
    let start = std::time::Instant::now();
    while !out.join("case.toml").exists() && start.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let second = sweep_example("jkr-sphere", out.to_str().unwrap(), &["--resume"]);
    let still_running = first.try_wait().unwrap().is_none();
    first.kill().ok();
    first.wait().unwrap();
    assert!(still_running, "the first sweep ended before the second started");
    assert!(!second.status.success());
    assert!(
        stderr(&second).contains("in use by another running"),
        "{}",
        stderr(&second)
    );
    // Once the first has ended (here killed), the directory is free: its lock died with it.
    let third = sweep_example(
        "jkr-sphere",
        out.to_str().unwrap(),
        &["--overwrite", "--steps", "1"],
    );
    assert!(
        third.status.success() || stderr(&third).contains("did not converge"),
        "{}",
        stderr(&third)
    );
    assert!(!stderr(&third).contains("in use"), "{}", stderr(&third));
}

#[test]
fn a_state_torn_between_two_steps_is_refused() {
    let d = dir("torn");
    let out = d.join("cycle");
    let out_s = out.to_str().unwrap();
    let hertz = ["--n", "32", "--steps", "3"];
    let o = sweep_example("hertz", out_s, &[&hertz[..], &["--save-states"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let start_from = |state: &std::path::Path, name: &str| {
        let into = d.join(name);
        sweep_example(
            "hertz",
            into.to_str().unwrap(),
            &[&hertz[..], &["--start-from", state.to_str().unwrap()]].concat(),
        )
    };
    // Whole states are taken.
    let good = start_from(&out.join("states/step-0002"), "good");
    assert!(good.status.success(), "{}", stderr(&good));
    // The gap of step 2 beside the pressures of step 3: refused, naming the part.
    std::fs::copy(
        out.join("states/step-0002/gap.npy"),
        out.join("states/step-0003/gap.npy"),
    )
    .unwrap();
    let torn = start_from(&out.join("states/step-0003"), "torn");
    assert!(!torn.status.success());
    assert!(
        stderr(&torn).contains("gap.npy is not the field its manifest"),
        "{}",
        stderr(&torn)
    );
    assert!(
        !d.join("torn").exists(),
        "a refused start leaves no directory behind"
    );
    // A state left between the two renames of a save (only state.new) is whole and taken.
    std::fs::rename(out.join("state"), out.join("state.new")).unwrap();
    let o = sweep_example(
        "hertz",
        out_s,
        &[&hertz[..], &["--save-states", "--resume"]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn what_a_user_reads_warnings_comparisons_and_paths_beside_the_case() {
    let d = dir("reads");
    let sphere = |approach: &str, out: &std::path::Path| {
        roughcontact(&[
            "solve",
            "--sphere-radius",
            "1e-6",
            "--modulus",
            "1e9",
            "--length",
            "5e-7",
            "--n",
            "32",
            "--approach",
            approach,
            "--no-png",
            "--out",
            out.to_str().unwrap(),
        ])
    };
    // A free-grid sphere whose contact fills the grid: warned, also in the summary.
    let filled = d.join("filled");
    let o = sphere("8e-8", &filled);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("reaches the edge of the free grid"),
        "{}",
        stderr(&o)
    );
    let warnings = json(&filled.join("summary.json"))["warnings"].to_string();
    assert!(warnings.contains("reaches the edge"), "{warnings}");
    assert!(stdout(&o).contains(", converged"), "{}", stdout(&o));
    // Inside the grid: no warning.
    let o = sphere("1e-8", &d.join("inside"));
    assert!(!stderr(&o).contains("edge"), "{}", stderr(&o));
    // A case file's surface is found beside the case file, wherever the command runs.
    let cases = d.join("cases");
    std::fs::create_dir_all(&cases).unwrap();
    let o = roughcontact(&[
        "generate",
        "--n",
        "32",
        "--length",
        "1e-5",
        "--no-png",
        "-o",
        cases.join("s.npy").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(
        cases.join("case.toml"),
        "surface = \"s.npy\"\nmodulus = 25e6\nmean_pressure = 2e5\nno_such_thing = 1\n",
    )
    .unwrap();
    let case = cases.join("case.toml");
    let o = roughcontact(&["solve", "--config", case.to_str().unwrap()]);
    assert!(
        stderr(&o).contains("unknown key `no_such_thing`"),
        "{}",
        stderr(&o)
    );
    std::fs::write(
        &case,
        "surface = \"s.npy\"\nmodulus = 25e6\nmean_pressure = 2e5\n",
    )
    .unwrap();
    let o = roughcontact(&[
        "solve",
        "--config",
        case.to_str().unwrap(),
        "--no-png",
        "--out",
        d.join("beside").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // A smooth sphere without adhesion is compared with Hertz; load steps print their areas.
    let o = sweep_example(
        "hertz",
        d.join("hertz").to_str().unwrap(),
        &["--n", "32", "--steps", "2"],
    );
    assert!(
        stdout(&o).contains("Hertz at the deepest approach"),
        "{}",
        stdout(&o)
    );
    let o = sweep_example(
        "hertz",
        d.join("loads").to_str().unwrap(),
        &["--n", "32", "--mean-pressures", "1e7,2e7,1e7"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let table = stdout(&o);
    assert!(table.contains("mean pressure [Pa]  contact area"), "{table}");
    assert_eq!(
        table
            .lines()
            .filter(|l| l.ends_with("loading") || l.ends_with("unloading"))
            .count(),
        3
    );
}

/// `sweep --pull-off-step`: the path goes in only, then the library's pull-off search runs
/// from its last state: the same force as `ContactProblem::pull_off` called directly, its
/// rows after the path's, and a search cut short is redone from the path's kept state.
#[test]
fn sweep_pull_off_search_is_the_library_search_and_resumes() {
    const CASE: &str = "sphere_radius = 1e-6\nmodulus = 1e9\nlaw = \"point\"\nz0 = 1e-9\n\
                        work_of_adhesion = 0.1\nn = 32\nlength = 2e-7\n";
    let d = dir("pull-off");
    let config = d.join("case.toml");
    let path = "from = -3e-9\nto = 1e-9\nsteps = 4\npull_off_step = 1e-9\npull_off_floor = -8e-9\n";
    std::fs::write(&config, format!("{CASE}{path}")).unwrap();
    let out = d.join("run");
    let run = |extra: &[&str]| {
        let mut a = vec![
            "sweep",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        a.extend(extra);
        roughcontact(&a)
    };
    let sweep = |extra: &[&str]| {
        let o = run(extra);
        assert!(o.status.success(), "{}", stderr(&o));
        o
    };
    sweep(&["--keep-steps", "1"]);
    let s = json(&out.join("summary.json"));
    let force = s["pull_off_force"].as_f64().unwrap();
    // The steps kept: the one asked for, and the path's last (the search's start).
    let kept = |k: usize| out.join(format!("states/step-{k:04}/gap.npy")).exists();
    assert!(kept(1) && kept(4) && !kept(2) && !kept(5));

    let mut case: case::Case = toml::from_str(CASE).unwrap();
    case.fill_defaults("unused");
    let problem = case.build().unwrap().problem;
    let settings = case.settings();
    let loading = solver::approach_cycle(-3e-9, 1e-9, 4)[..5].to_vec();
    let mut last = None;
    struct Keep<'a>(&'a mut Option<solver::AdhesiveState>);
    impl solver::Observer for Keep<'_> {
        fn step(&mut self, _: usize, _: &solver::SweepPoint, s: &solver::AdhesiveState) -> bool {
            *self.0 = Some(s.clone());
            true
        }
    }
    problem
        .sweep(&loading, Some(1e-9), &settings, None, &mut Keep(&mut last))
        .unwrap();
    let search = solver::PullOffSearch {
        step: 1e-9,
        floor: -8e-9,
        recovery: Some(0.5),
        refinement: 5,
        rate: None,
    };
    let direct = problem
        .pull_off(&search, &settings, last.unwrap(), &mut ())
        .unwrap();
    assert_eq!(force, -direct.force);
    assert!(direct.force > 0.0 && !direct.refined.is_empty());
    let csv = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(
        rows.len(),
        5 + direct.coarse.len() + direct.refined.len(),
        "{csv}"
    );
    assert!(rows[..5].iter().all(|r| r.contains(",loading,")), "{csv}");
    assert!(rows[5..].iter().all(|r| r.contains(",unloading,")), "{csv}");

    // Cut within the search: resuming redoes the search from the path's last state.
    let kept: Vec<&str> = csv.lines().take(1 + 7).collect();
    std::fs::write(out.join("curve.csv"), kept.join("\n") + "\n").unwrap();
    std::fs::remove_file(out.join("summary.json")).unwrap();
    let o = sweep(&["--keep-steps", "1", "--resume"]);
    assert!(
        stderr(&o).contains("resuming after 5 of 5 steps"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        json(&out.join("summary.json"))["pull_off_force"],
        s["pull_off_force"]
    );
    assert_eq!(
        std::fs::read_to_string(out.join("curve.csv"))
            .unwrap()
            .lines()
            .count(),
        csv.lines().count()
    );

    for (extra, message) in [
        (
            vec!["--pull-off-floor", "2e-9"],
            "--pull-off-floor (2e-9 m) must be below the path's last approach",
        ),
        (
            vec!["--pull-off-step", "0"],
            "--pull-off-step must be a positive length",
        ),
        (
            vec!["--pull-off-recovery", "1.5"],
            "--pull-off-recovery must be in (0, 1]",
        ),
        (
            vec!["--mean-pressures", "1e5"],
            "the pull-off search follows an approach path",
        ),
    ] {
        let o = run(&[&extra[..], &["--overwrite"]].concat());
        assert!(
            !o.status.success() && stderr(&o).contains(message),
            "{extra:?}: {}",
            stderr(&o)
        );
    }
}
