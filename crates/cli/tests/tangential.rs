//! A tangential path end to end: the flags reach the problem, the outputs are written, and
//! refusals name the flag.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("roughcontact-tangential-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// A Hertz contact 24 cells in radius (R = 1 mm, E* = 1 GPa, nu = 0.3) with `extra`.
fn sphere(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "solve",
        "--sphere-radius",
        "1e-3",
        "--n",
        "128",
        "--length",
        "128e-6",
        "--modulus",
        "1e9",
        "--load",
        "0.0184",
        "--out",
        out.to_str().unwrap(),
        "--no-png",
    ];
    args.extend_from_slice(extra);
    run(&args)
}

/// The body's Poisson's ratio and Coulomb's coefficient of every path here.
const COULOMB: [&str; 4] = ["--poisson", "0.3", "--friction-coefficient", "0.3"];

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `tangential.csv` in `out`, header first, split into cells.
fn table(out: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(out.join("tangential.csv"))
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn a_partial_slip_loop_writes_its_steps_fields_and_summary() {
    let out = dir("loop");
    let o = sphere(
        &out,
        &[
            &COULOMB[..],
            &[
                "--tangential-loads",
                "2e-3,4e-3,0,-4e-3,0,4e-3",
                "--tangential-angle",
                "1.5707963267948966",
            ],
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = table(&out);
    assert_eq!(rows[0][1], "force_x");
    assert_eq!(rows.len(), 7);
    // Along y: the force's x part vanishes, its y part follows the path.
    let fy: Vec<f64> = rows[1..].iter().map(|r| r[2].parse().unwrap()).collect();
    for (f, q) in fy.iter().zip([2e-3, 4e-3, 0.0, -4e-3, 0.0, 4e-3]) {
        assert!((f - q).abs() < 1e-12, "{f} vs {q}");
    }
    for name in ["shear_x", "shear_y", "slip_x", "slip_y"] {
        assert!(out.join(format!("{name}.npy")).exists(), "{name}.npy");
    }
    let summary = summary(&out);
    let t = &summary["tangential"];
    assert!((t["static_friction"].as_f64().unwrap() - 0.3 * 0.0184).abs() < 1e-12);
    assert_eq!(t["steps"], 6);
    assert!(t["frictional_work"].as_f64().unwrap() > 0.0 && t["all_converged"] == true);
    assert_eq!(summary["case"]["friction_coefficient"], 0.3);
}

/// A rigid counterface couples the path to the normal contact: rounds of both solves, the load
/// held, the approach moved.
#[test]
fn a_rigid_counterface_couples_the_path() {
    let out = dir("rigid");
    let o = sphere(
        &out,
        &[
            &COULOMB[..],
            &["--counterface", "rigid", "--tangential-loads", "2e-3,4e-3"],
        ]
        .concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = table(&out);
    let column = |name: &str| rows[0].iter().position(|c| c == name).unwrap();
    let (load, approach, rounds) = (
        column("normal_load"),
        column("approach"),
        column("coupling_iterations"),
    );
    let summary = summary(&out);
    let normal_approach = summary["approach"].as_f64().unwrap();
    for row in &rows[1..] {
        assert!((row[load].parse::<f64>().unwrap() - 0.0184).abs() < 1e-12);
        assert!(row[rounds].parse::<usize>().unwrap() >= 2);
        assert!(row[approach].parse::<f64>().unwrap() != normal_approach);
    }
    assert_eq!(summary["case"]["counterface"], "rigid");
}

#[test]
fn more_than_the_contact_carries_is_reported_as_sliding() {
    let out = dir("slide");
    let o = sphere(
        &out,
        &[&COULOMB[..], &["--tangential-loads", "1e-3,0.1,0.2"]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("ended at step 2 of 3"), "{}", stderr(&o));
    let rows = table(&out);
    let (header, last) = (&rows[0], rows.last().unwrap());
    let column = |name: &str| header.iter().position(|c| c == name).unwrap();
    assert_eq!(last[column("displacement_x")], "NaN");
    assert_eq!(last[column("gross_sliding")], "true");
}

#[test]
fn bad_tangential_input_is_refused_by_name() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "--poisson",
                "0.3",
                "--friction-coefficient",
                "-0.1",
                "--tangential-loads",
                "1e-3",
            ],
            "--friction-coefficient must be a finite number >= 0",
        ),
        (
            &[
                "--poisson",
                "0.3",
                "--shear-strength",
                "-5",
                "--tangential-loads",
                "1e-3",
            ],
            "--shear-strength must be a finite shear stress >= 0 Pa",
        ),
        (&COULOMB, "bound a tangential path's shear"),
        (
            &["--tangential-loads", "1e-3"],
            "a tangential path needs friction",
        ),
        (
            &["--friction-coefficient", "0.3", "--tangential-loads", "1e-3"],
            "friction needs the body's --poisson",
        ),
        (
            &[
                "--poisson",
                "0.3",
                "--friction-coefficient",
                "0.3",
                "--tangential-angle",
                "1",
            ],
            "--tangential-angle orients a tangential path",
        ),
        (
            &[
                "--poisson",
                "0.3",
                "--friction-coefficient",
                "0.3",
                "--tangential-loads",
                "1e-3",
                "--tangential-displacements",
                "1e-9",
            ],
            "cannot be used with",
        ),
        (&["--poisson", "0.3"], "--poisson does not apply to this case"),
        (
            &["--counterface", "rigid"],
            "--counterface does not apply to this case",
        ),
        (
            &[
                "--thickness",
                "5e-6",
                "--poisson",
                "0.3",
                "--friction-coefficient",
                "0.3",
                "--tangential-loads",
                "1e-3",
            ],
            "periodic grids only",
        ),
    ];
    for (k, (extra, message)) in cases.iter().enumerate() {
        let o = sphere(&dir(&format!("bad{k}")), extra);
        assert!(!o.status.success(), "{extra:?} was accepted");
        assert!(stderr(&o).contains(message), "{extra:?}: {}", stderr(&o));
    }
    // A sweep has no tangential path.
    let o = run(&[
        "sweep",
        "--sphere-radius",
        "1e-3",
        "--n",
        "64",
        "--length",
        "128e-6",
        "--modulus",
        "1e9",
        "--approaches",
        "1e-7",
        "--poisson",
        "0.3",
        "--friction-coefficient",
        "0.3",
        "--out",
        dir("sweep").to_str().unwrap(),
        "--no-png",
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("follows a single normal solve"),
        "{}",
        stderr(&o)
    );
    // No normal load: nothing to shear.
    let o = run(&[
        "solve",
        "--sphere-radius",
        "1e-3",
        "--n",
        "64",
        "--length",
        "128e-6",
        "--modulus",
        "1e9",
        "--load",
        "0",
        "--poisson",
        "0.3",
        "--friction-coefficient",
        "0.3",
        "--tangential-loads",
        "1e-3",
        "--out",
        dir("unloaded").to_str().unwrap(),
        "--no-png",
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("needs a normal contact"),
        "{}",
        stderr(&o)
    );
}

/// tangential.csv without its wall times.
fn rows(out: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(out.join("tangential.csv")).unwrap_or_default();
    text.lines()
        .map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string())
        .collect()
}

/// A fretting path run whole, and run killed (SIGKILL) once `after` steps are written and then
/// resumed: the same rows (wall times aside) and fields to the bit. With `torn`, the saved
/// state is found where a kill between its two renames leaves it (`tangential_state.new`).
fn killed_and_resumed(name: &str, extra: &[&str], after: usize, torn: bool) {
    let d = dir(name);
    let cycle: Vec<String> = (0..48)
        .map(|k| format!("{:e}", 4e-3 * (k as f64 * std::f64::consts::PI / 12.0).sin()))
        .collect();
    let cycle = cycle.join(",");
    let mut path = [&COULOMB[..], &["--tangential-loads", &cycle]].concat();
    path.extend_from_slice(extra);
    let args = |out: &Path| {
        let mut args: Vec<String> = [
            "solve",
            "--sphere-radius",
            "1e-3",
            "--n",
            "128",
            "--length",
            "128e-6",
            "--modulus",
            "1e9",
            "--load",
            "0.0184",
            "--no-png",
            "--out",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        args.push(out.to_str().unwrap().into());
        args.extend(path.iter().map(|s| s.to_string()));
        args
    };
    let whole = d.join("whole");
    let o = run(&args(&whole).iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", stderr(&o));
    let killed = d.join("killed");
    let mut child = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args(&killed))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while rows(&killed).len() <= after && started.elapsed() < Duration::from_secs(300) {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let written = rows(&killed).len();
    assert!(
        written < rows(&whole).len(),
        "the path ended before it was killed"
    );
    if torn {
        let state = killed.join("tangential_state");
        std::fs::rename(&state, killed.join("tangential_state.new")).unwrap();
    }
    let mut resume = args(&killed);
    resume.push("--resume".into());
    let o = run(&resume.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("resuming the tangential path after"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        rows(&killed),
        rows(&whole),
        "killed after {written} rows and resumed"
    );
    for f in ["shear_x.npy", "shear_y.npy", "slip_x.npy", "slip_y.npy"] {
        assert!(
            std::fs::read(killed.join(f)).unwrap() == std::fs::read(whole.join(f)).unwrap(),
            "{f}"
        );
    }
    assert_eq!(summary(&killed)["tangential"], summary(&whole)["tangential"]);
}

#[test]
fn a_fretting_path_killed_and_resumed_is_the_same_to_the_bit() {
    killed_and_resumed("resume", &[], 10, false);
}

#[test]
fn a_coupled_path_killed_and_resumed_is_the_same_to_the_bit() {
    killed_and_resumed("resume-coupled", &["--counterface", "rigid"], 6, true);
}

#[test]
fn resume_is_refused_where_there_is_nothing_to_continue() {
    let out = dir("resume-nothing");
    let o = sphere(&out, &["--resume"]);
    assert!(
        !o.status.success() && stderr(&o).contains("this solve has none"),
        "{}",
        stderr(&o)
    );
    // Where nothing was begun the path runs whole; a plain solve's run is not continued.
    let path = [
        "--poisson",
        "0.3",
        "--friction-coefficient",
        "0.3",
        "--tangential-loads",
        "1e-3",
    ];
    let o = sphere(&out, &[&path[..], &["--resume"]].concat());
    assert!(
        o.status.success() && out.join("tangential.csv").exists(),
        "{}",
        stderr(&o)
    );
    let plain = dir("resume-plain");
    assert!(sphere(&plain, &[]).status.success());
    let o = sphere(&plain, &[&path[..], &["--resume"]].concat());
    assert!(
        !o.status.success() && stderr(&o).contains("holds no tangential path to continue"),
        "{}",
        stderr(&o)
    );
    let mut other = path.to_vec();
    other[5] = "2e-3";
    let o = sphere(&out, &[&other[..], &["--resume"]].concat());
    assert!(
        !o.status.success() && stderr(&o).contains("holds a different case"),
        "{}",
        stderr(&o)
    );
}
