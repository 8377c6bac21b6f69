//! Models with a history end to end, a hardness (its permanent set) and a viscoelastic body
//! (its branches and time): a sweep killed and resumed gives the same curve and fields to the
//! bit; refusals name the flag.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("roughcontact-history-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The Hertz example (R = 1 um, E* = 1 GPa, Hertz's peak 45 MPa at the deepest step) with a
/// hardness of 30 MPa, in 30 steps and out again.
fn args(out: &Path) -> Vec<String> {
    [
        "sweep",
        "--example",
        "hertz",
        "--hardness",
        "3e7",
        "--steps",
        "30",
        "--no-png",
        "--out",
        out.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

/// `solve` of an adhesive sphere (R = 1 um, 64^2 cells across 200 nm, E* = 1 GPa,
/// w0 = 50 mJ/m^2) with `extra` flags.
fn sphere_solve(extra: &[&str]) -> Vec<String> {
    let base = [
        "solve",
        "--sphere-radius",
        "1e-6",
        "--n",
        "64",
        "--length",
        "2e-7",
        "--modulus",
        "1e9",
        "--work-of-adhesion",
        "0.05",
    ];
    base.iter().chain(extra).map(|s| s.to_string()).collect()
}

fn run(args: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// curve.csv without its wall times.
fn curve(out: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let wall = header.iter().position(|h| *h == "wall_time_s").unwrap();
    text.lines()
        .map(|l| {
            let mut f: Vec<&str> = l.split(',').collect();
            f.remove(wall);
            f.join(",")
        })
        .collect()
}

/// Runs the sweep of `args` whole into `<d>/whole`, then into `<d>/killed` killed (SIGKILL)
/// once `rows` rows are written and resumed: the curves (wall times aside) and the `files`
/// must be the same to the bit. Returns the whole run's directory.
fn killed_and_resumed(d: &Path, args: impl Fn(&Path) -> Vec<String>, rows: usize, files: &[&str]) -> PathBuf {
    let whole = d.join("whole");
    let o = run(&args(&whole));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let reference = curve(&whole);
    let killed = d.join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args(&killed))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    loop {
        let written = std::fs::read_to_string(killed.join("curve.csv")).map_or(0, |t| t.lines().count());
        if written > rows || started.elapsed() > Duration::from_secs(300) {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    let written = curve(&killed).len();
    assert!(written < reference.len(), "the sweep ended before it was killed");
    let mut resume = args(&killed);
    resume.push("--resume".into());
    let o = run(&resume);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        curve(&killed),
        reference,
        "killed ({status}) after {written} rows and resumed"
    );
    for f in files {
        assert!(
            std::fs::read(killed.join(f)).unwrap() == std::fs::read(whole.join(f)).unwrap(),
            "{f}"
        );
    }
    whole
}

/// The last row's value of the column `name` in `rows` (header first).
fn column<'a>(rows: &'a [String], name: &str) -> &'a str {
    let k = rows[0].split(',').position(|c| c == name).unwrap();
    rows.last().unwrap().split(',').nth(k).unwrap()
}

#[test]
fn a_plastic_sweep_killed_and_resumed_is_the_same_to_the_bit() {
    let whole = killed_and_resumed(&dir("resume"), args, 8, &["plastic.npy"]);
    let reference = curve(&whole);
    assert_eq!(reference.len(), 1 + 61);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("summary.json")).unwrap()).unwrap();
    assert!(s["plastic_work"].as_f64().unwrap() > 0.0, "{s}");
    assert!(s["permanent_set_volume"].is_null());
    assert!(
        column(&reference, "permanent_set_volume").parse::<f64>().unwrap() > 0.0,
        "a permanent set after unloading"
    );
}

/// The JKR example's sphere on a standard linear solid (E0 = 10 E_inf, tau = 1 s) cycled in
/// 40 steps of 0.1 s each way.
fn viscoelastic(out: &Path) -> Vec<String> {
    [
        "sweep",
        "--example",
        "jkr-sphere",
        "--maxwell-moduli",
        "9e9",
        "--maxwell-times",
        "1",
        "--step-time",
        "0.1",
        "--steps",
        "40",
        "--no-png",
        "--out",
        out.to_str().unwrap(),
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn a_viscoelastic_sweep_killed_and_resumed_is_the_same_to_the_bit() {
    let files = [
        "state/branch_stress_0.npy",
        "state/displacement.npy",
        "state/manifest.json",
    ];
    let whole = killed_and_resumed(&dir("viscoelastic"), viscoelastic, 12, &files);
    let reference = curve(&whole);
    assert_eq!(column(&reference, "time"), "8e0");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("summary.json")).unwrap()).unwrap();
    assert!(s["viscous_work"].as_f64().unwrap() > 0.0, "{s}");
    // A state saved as an earlier version did (the springs' displacements) is refused by name.
    let state = whole.join("state");
    let manifest = std::fs::read_to_string(state.join("manifest.json")).unwrap();
    std::fs::write(
        state.join("manifest.json"),
        manifest.replace("branch_stress_0", "branch_0"),
    )
    .unwrap();
    std::fs::rename(state.join("branch_stress_0.npy"), state.join("branch_0.npy")).unwrap();
    let mut again = viscoelastic(&whole.with_file_name("from-old"));
    again.extend(["--start-from".into(), state.to_str().unwrap().into()]);
    let o = run(&again);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("earlier version") && err.contains("rerun"), "{err}");
}

#[test]
fn bad_viscoelastic_input_is_refused_by_name() {
    let d = dir("viscoelastic-refused");
    let base = viscoelastic(&d.join("out"));
    // (flag, value, what the message says)
    let cases: [(&str, &str, &str); 6] = [
        (
            "--maxwell-moduli",
            "-9e9",
            "--maxwell-moduli values must be finite and > 0 Pa",
        ),
        (
            "--maxwell-times",
            "0",
            "--maxwell-times values must be finite and > 0 s",
        ),
        (
            "--maxwell-times",
            "1,2",
            "--maxwell-times must hold one time a branch modulus",
        ),
        (
            "--step-time",
            "-0.1",
            "--step-time must be a finite duration > 0 s",
        ),
        (
            "--step-time",
            "",
            "give each step a time, --step-time S or --times",
        ),
        (
            "--maxwell-moduli",
            "",
            "--step-time times a viscoelastic body's steps, and this body is elastic",
        ),
    ];
    for (flag, value, says) in cases {
        let mut a = base.clone();
        let at = a.iter().position(|f| f == flag).unwrap();
        if value.is_empty() {
            a.drain(at..at + 2);
            if flag == "--maxwell-moduli" {
                let t = a.iter().position(|f| f == "--maxwell-times").unwrap();
                a.drain(t..t + 2);
            }
        } else {
            a[at + 1] = value.into();
        }
        let o = run(&a);
        assert!(!o.status.success(), "{flag} {value}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{flag} {value}: {err}");
    }
    // Times that go backwards, and a single solve, whose answer would depend on a history.
    let mut a = base.clone();
    let at = a.iter().position(|f| f == "--step-time").unwrap();
    a.splice(
        at..at + 2,
        ["--approaches", "1e-9,0,-1e-9", "--times", "0,2,1"].map(String::from),
    );
    a.retain(|f| f != "--steps" && f != "40");
    let o = run(&a);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--times go backwards"),
        "{err}"
    );
    let out = d.join("solve");
    let o = run(&sphere_solve(&[
        "--z0",
        "1e-9",
        "--maxwell-moduli",
        "9e9",
        "--maxwell-times",
        "1",
        "--approach",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("a viscoelastic body"),
        "{err}"
    );
}

#[test]
fn bad_hardness_and_laws_or_methods_that_cannot_take_it_are_refused_by_name() {
    let d = dir("refused");
    for bad in ["0", "-1e7", "nan", "inf"] {
        let mut a = args(&d.join(format!("bad{bad}")));
        a[4] = bad.to_string();
        let o = run(&a);
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--hardness must be a finite"), "{bad}: {err}");
    }
    // The descent takes a hardness with the laws of a cell's own gap only; a hardness below
    // the exponential law's pull at contact (w0 / rho = 5e7 Pa) would never hold a contact.
    for (law, range, err_has) in [
        (
            "surface-energy",
            "--z0",
            "takes a hardness with the laws of a cell's own gap",
        ),
        ("exponential", "--range", "attraction at contact"),
    ] {
        let o = run(&sphere_solve(&[
            range,
            "1e-9",
            "--law",
            law,
            "--hardness",
            "3e7",
            "--approach",
            "1e-9",
            "--solver",
            "energy",
            "--out",
            d.join(law).to_str().unwrap(),
        ]));
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(err_has) && err.contains("hardness"), "{err}");
    }
}

#[test]
fn a_curve_written_before_the_plastic_time_or_energy_columns_resumes_with_them() {
    let d = dir("old-curve");
    let out = d.join("old");
    let mut a = args(&out);
    // The Hertz example as it is, elastic.
    a.drain(3..7);
    let o = run(&a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    a.push("--resume".into());
    // The energies of the old rows are unknown: empty.
    let cut = |l: &str, n: usize| l.rsplitn(n + 1, ',').last().unwrap().to_string();
    let upgraded: String = text
        .lines()
        .enumerate()
        .map(|(k, l)| if k == 0 { l.to_string() } else { cut(l, 2) + ",," } + "\n")
        .collect();
    // Without the plastic, time and energy columns, without time and energies, without energies.
    for columns in [6, 3, 2] {
        let old: String = text.lines().map(|l| cut(l, columns) + "\n").collect();
        std::fs::write(out.join("curve.csv"), &old).unwrap();
        let o = run(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(std::fs::read_to_string(out.join("curve.csv")).unwrap(), upgraded);
    }
}

#[test]
fn the_bench_caps_at_a_hardness_meets_its_tight_solve_and_refuses_one_below_the_load() {
    let d = dir("bench");
    let json = d.join("bench.json");
    let o = run(&[
        "bench",
        "--sizes",
        "64",
        "--hardness",
        "0.1",
        "--pressure",
        "0.03",
        "--check",
        "--solver",
        "preconditioned",
        "--json",
        json.to_str().unwrap(),
    ]
    .map(String::from));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let row = &rows[0];
    assert_eq!(row["converged"], true);
    assert_eq!(row["hardness"], 0.1);
    // Most of the contact is held at H on this steep surface.
    let (area, plastic) = (
        row["contact_area_fraction"].as_f64().unwrap(),
        row["plastic_area_fraction"].as_f64().unwrap(),
    );
    assert!(plastic > 0.9 * area && plastic <= area, "{plastic} of {area}");
    assert_eq!(row["contact_cells_differing"], 0);
    assert_eq!(row["cells_at_hardness_differing"], 0);
    for bad in ["0.01", "nan"] {
        let o = run(&["bench", "--sizes", "64", "--pressure", "0.03", "--hardness", bad].map(String::from));
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--hardness must be a finite H"), "{bad}: {err}");
    }
}
