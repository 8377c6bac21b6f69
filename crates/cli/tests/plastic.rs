//! A hardness end to end: a load-unload sweep killed and resumed gives the same curve and the
//! same permanent set to the bit; refusals name the flag.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("roughcontact-plastic-{}-{name}", std::process::id()));
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

#[test]
fn a_plastic_sweep_killed_and_resumed_is_the_same_to_the_bit() {
    let d = dir("resume");
    let whole = d.join("whole");
    let o = run(&args(&whole));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let reference = curve(&whole);
    assert_eq!(reference.len(), 1 + 61);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(whole.join("summary.json")).unwrap()).unwrap();
    assert!(s["plastic_work"].as_f64().unwrap() > 0.0, "{s}");
    assert!(s["permanent_set_volume"].is_null());
    let last: Vec<&str> = reference.last().unwrap().split(',').collect();
    assert!(
        last[last.len() - 2].parse::<f64>().unwrap() > 0.0,
        "a permanent set after unloading"
    );
    let set = std::fs::read(whole.join("plastic.npy")).unwrap();

    // Killed (SIGKILL) once a few steps are written, then resumed.
    let killed = d.join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args(&killed))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    loop {
        let rows = std::fs::read_to_string(killed.join("curve.csv")).map_or(0, |t| t.lines().count());
        // The header and eight steps.
        if rows > 8 || started.elapsed() > Duration::from_secs(300) {
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
    assert!(std::fs::read(killed.join("plastic.npy")).unwrap() == set);
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
        let o = run(&[
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
        ]
        .map(String::from));
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(err_has) && err.contains("hardness"), "{err}");
    }
}

#[test]
fn a_curve_written_before_the_plastic_columns_resumes_with_them() {
    let d = dir("old-curve");
    let out = d.join("old");
    let mut a = args(&out);
    // The Hertz example as it is, elastic.
    a.drain(3..7);
    let o = run(&a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("curve.csv")).unwrap();
    let old: String = text
        .lines()
        .map(|l| l.rsplitn(4, ',').last().unwrap().to_string() + "\n")
        .collect();
    std::fs::write(out.join("curve.csv"), &old).unwrap();
    a.push("--resume".into());
    let o = run(&a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(out.join("curve.csv")).unwrap(), text);
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
