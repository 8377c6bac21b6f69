//! Bad input and faults met by a new user, each with the outcome it must have: a clear error
//! (status 1, naming what is wrong) or a run that does what it says, never a panic (101), an
//! abort (134), a hang or a silently dropped value. `docs/reliability.md` lists them.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn roughcontact_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("the binary runs")
}

fn fresh(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("reliability-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sample(name: &str) -> String {
    format!(
        "{}/../../data/topography-samples/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The outcome a case must have.
enum Must {
    /// Exit 0.
    Succeed,
    /// Exit 1 with this fragment in the error.
    Refuse(&'static str),
}

/// Runs `args` in `dir` and checks the outcome; stdout goes to `/dev/full` when `full`.
fn check(dir: &Path, args: &[&str], must: Must) -> Output {
    let o = roughcontact_in(dir, args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !err.contains("panicked") && o.status.code() != Some(101) && o.status.code() != Some(134),
        "{args:?} panicked or aborted: {err}"
    );
    match must {
        Must::Succeed => assert!(o.status.success(), "{args:?} failed: {err}"),
        Must::Refuse(fragment) => {
            assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
            assert!(err.contains(fragment), "{args:?}: `{fragment}` not in: {err}");
        }
    }
    o
}

const STUDY_BASE: &str =
    "[case]\nlength = 1e-6\nrms_height = 1e-8\nmodulus = 1e9\nmean_pressure = 1e6\nn = 32\n";

#[test]
fn studies_check_their_runs_before_running_and_write_real_csv() {
    let d = fresh("study");
    // Twelve axes of ten values: 1e12 runs.
    let product: String = "abcdefghijkl"
        .chars()
        .map(|c| format!("{c} = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n"))
        .collect();
    for (name, axes, fragment) in [
        (
            "float-n",
            "seed = [1, 2]\nn = [32, 48.5]\n",
            "`n` must be a whole number >= 0, got 48.5",
        ),
        (
            "string-seed",
            "seed = [1, \"two\"]\n",
            "`seed` must be a whole number >= 0, got \"two\"",
        ),
        ("unknown", "bogus = [1, 2]\n", "unknown key `bogus`"),
        (
            "not-applicable",
            "seed = [1, 2]\nexact_sphere = [true]\n",
            "--exact-sphere does not apply",
        ),
        ("product", &product, "a study of 1.000e12 runs needs about"),
    ] {
        let file = d.join(format!("{name}.toml"));
        std::fs::write(&file, format!("command = \"solve\"\n{STUDY_BASE}[axes]\n{axes}")).unwrap();
        check(&d, &["study", file.to_str().unwrap()], Must::Refuse(fragment));
        assert!(
            !d.join("run/study").join(name).exists(),
            "{name}: a refused study made its directory"
        );
    }
    // A run that fails with a message of several lines: the tables stay tables.
    let file = d.join("failing.toml");
    std::fs::write(
        &file,
        format!("command = \"solve\"\n{STUDY_BASE}[axes]\nseed = [1, 2]\nmodulus = [1e9, -1.0]\n"),
    )
    .unwrap();
    check(&d, &["study", file.to_str().unwrap()], Must::Succeed);
    let table = std::fs::read_to_string(d.join("run/study/failing/study.csv")).unwrap();
    let groups = std::fs::read_to_string(d.join("run/study/failing/study-groups.csv")).unwrap();
    assert!(
        table.contains("failed") && groups.starts_with("modulus,runs"),
        "{table}\n{groups}"
    );
}

#[test]
fn a_run_under_way_in_another_study_is_left_to_it() {
    let d = fresh("busy");
    let file = d.join("s.toml");
    std::fs::write(
        &file,
        format!("command = \"solve\"\n{STUDY_BASE}[axes]\nseed = [1, 2]\n"),
    )
    .unwrap();
    // This process holds run seed=1's lock, as a second study running it would.
    let run = d.join("run/study/s/runs/seed=1");
    std::fs::create_dir_all(&run).unwrap();
    let lock = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(run.join(".lock"))
        .unwrap();
    lock.try_lock().unwrap();
    let o = check(&d, &["study", file.to_str().unwrap()], Must::Succeed);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("1 under way in another process") && out.contains("0 failed"),
        "{out}"
    );
    assert!(
        !run.join("error.txt").exists(),
        "the run under way elsewhere got an error.txt"
    );
    let table = std::fs::read_to_string(d.join("run/study/s/study.csv")).unwrap();
    assert!(table.contains("under way elsewhere"), "{table}");
    drop(lock);
    // The other study gone, the same command runs it.
    let o = check(&d, &["study", file.to_str().unwrap()], Must::Succeed);
    assert!(String::from_utf8_lossy(&o.stdout).contains("2 finished"));
}

#[test]
fn values_that_would_be_dropped_are_refused() {
    let d = fresh("dropped");
    check(
        &d,
        &[
            "generate",
            "--n",
            "32",
            "--length",
            "1e-6",
            "--rms-height",
            "1e-8",
            "-o",
            "g.npy",
            "--no-png",
        ],
        Must::Succeed,
    );
    let solve = ["solve", "--modulus", "1e9", "--mean-pressure", "1e6", "--no-png"];
    check(
        &d,
        &["stats", "g.npy", "--not-periodic"],
        Must::Refuse("--not-periodic, periodic=False) does not apply"),
    );
    for (extra, fragment) in [
        (
            &["--surface", "g.npy", "--length", "1"][..],
            "so `length` = 1e0 m does not apply",
        ),
        (
            &["--surface", "g.npy", "--length-y", "2e-6"],
            "so `length_y` = 2e-6 m does not apply",
        ),
        (
            &["--sphere-radius", "1e-6", "--length", "1e-7", "--fill-unmeasured"],
            "--fill-unmeasured does not apply",
        ),
        (
            &["--sphere-radius", "1e-6", "--length", "1e-7", "--seed", "3"],
            "--seed does not apply",
        ),
        (
            &["--sphere-radius", "1e-6", "--length", "1e-7", "--hurst", "0.5"],
            "--hurst does not apply",
        ),
        (
            &["--rms-height", "1e-8", "--length", "1e-6", "--exact-sphere"],
            "--exact-sphere does not apply",
        ),
        (
            &["--sphere-radius", "1e-6", "--length", "1e-7", "--z0", "1e-9"],
            "--z0 does not apply",
        ),
        (
            &["--sphere-radius", "1e-6", "--length", "1e-7", "--solver", "flow"],
            "--solver does not apply",
        ),
        (
            &[
                "--sphere-radius",
                "1e-6",
                "--length",
                "1e-7",
                "--law",
                "exponential",
                "--work-of-adhesion",
                "0.05",
                "--range",
                "1e-9",
                "--z0",
                "1e-9",
            ],
            "--z0 does not apply",
        ),
        (
            &[
                "--sphere-radius",
                "1e-6",
                "--length",
                "1e-7",
                "--law",
                "none",
                "--work-of-adhesion",
                "0.05",
            ],
            "--work-of-adhesion does not apply",
        ),
        (
            &[
                "--sphere-radius",
                "1e-6",
                "--length",
                "1e-7",
                "--max-unmeasured",
                "0.5",
            ],
            "--max-unmeasured does not apply",
        ),
    ] {
        let out = format!("out-{}", extra.join("_").replace(['-', '.'], ""));
        let args = [&solve[..], extra, &["--out", &out]].concat();
        check(&d, &args, Must::Refuse(fragment));
        assert!(
            !d.join(&out).exists(),
            "{extra:?}: a refused run made its directory"
        );
    }
    check(
        &d,
        &[
            "sweep",
            "--example",
            "challenge-small",
            "--max-step",
            "1e-9",
            "--out",
            "split",
        ],
        Must::Refuse("--max-step 1e-9 does not apply to a path of loads"),
    );
    check(
        &d,
        &[
            "sweep",
            "--example",
            "hertz",
            "--keep-steps",
            "7,1000",
            "--out",
            "kept",
        ],
        Must::Refuse("--keep-steps 1000: the path has 21 steps, numbered 0 to 20"),
    );
    for (args, fragment) in [
        (
            &["--n", "32", "--nx", "64"][..],
            "give --n (a square grid) or --nx and --ny, not both",
        ),
        (
            &["--n", "32", "--length", "1e-6", "--length-x", "2e-6"],
            "give --length (a square box) or --length-x and --length-y, not both",
        ),
    ] {
        let args = [&["generate", "-o", "two.npy", "--no-png"][..], args].concat();
        check(&d, &args, Must::Refuse(fragment));
    }
    // An optional-value flag takes its value only after `=`: the next flag stays a flag.
    check(
        &d,
        &[
            "solve",
            "--exact-sphere",
            "--sphere-radius",
            "1e-6",
            "--length",
            "1e-7",
            "--n",
            "32",
            "--modulus",
            "1e9",
            "--load",
            "1e-9",
            "--no-png",
            "--out",
            "exact",
        ],
        Must::Succeed,
    );
    check(
        &d,
        &[
            "solve",
            "--exact-sphere=false",
            "--sphere-radius",
            "1e-6",
            "--length",
            "1e-7",
            "--n",
            "32",
            "--modulus",
            "1e9",
            "--load",
            "1e-9",
            "--no-png",
            "--out",
            "exact2",
        ],
        Must::Succeed,
    );
    // --resume continues a sweep only: a solve's directory is left as it was.
    let summary = std::fs::read_to_string(d.join("exact/summary.json")).unwrap();
    check(
        &d,
        &["sweep", "--example", "hertz", "--resume", "--out", "exact"],
        Must::Refuse("holds no sweep to continue"),
    );
    assert_eq!(
        std::fs::read_to_string(d.join("exact/summary.json")).unwrap(),
        summary
    );
    assert!(!d.join("exact/curve.csv").exists());
    // Nor a solve's tangential path, which solve --resume continues.
    let path = [
        "solve",
        "--sphere-radius",
        "1e-3",
        "--n",
        "32",
        "--length",
        "64e-6",
        "--modulus",
        "1e9",
        "--load",
        "1e-3",
        "--poisson",
        "0.3",
        "--friction-coefficient",
        "0.3",
        "--tangential-loads",
        "1e-4",
        "--no-png",
        "--out",
        "sheared",
    ];
    check(&d, &path, Must::Succeed);
    check(
        &d,
        &["sweep", "--example", "hertz", "--resume", "--out", "sheared"],
        Must::Refuse("holds no sweep to continue"),
    );
    assert!(!d.join("sheared/curve.csv").exists());
    check(&d, &[&path[..], &["--resume"]].concat(), Must::Succeed);
}

#[test]
fn results_that_are_not_finite_are_errors_and_nothing_hangs() {
    let d = fresh("finite");
    check(
        &d,
        &[
            "generate",
            "--n",
            "32",
            "--length",
            "1e-6",
            "--rms-height",
            "1e300",
            "-o",
            "huge.npy",
            "--no-png",
        ],
        Must::Refuse("at most 1e100"),
    );
    check(
        &d,
        &[
            "generate",
            "--n",
            "32",
            "--length",
            "1e-6",
            "--rms-height",
            "1e90",
            "-o",
            "big.npy",
            "--no-png",
        ],
        Must::Succeed,
    );
    // Its statistics stay finite: the sidecar reads back.
    check(&d, &["stats", "big.npy"], Must::Succeed);
    for extra in [
        &["--mean-pressure", "1e5"][..],
        &["--approach", "1e90"],
        &["--approach", "1e90", "--work-of-adhesion", "1", "--z0", "1e-9"],
    ] {
        let args = [
            &[
                "solve",
                "--surface",
                "big.npy",
                "--modulus",
                "1e300",
                "--out",
                "nan",
            ][..],
            extra,
        ]
        .concat();
        check(&d, &args, Must::Refuse("not a finite number"));
        assert!(!d.join("nan/summary.json").exists() && !d.join("nan/pressure.png").exists());
    }
}

#[test]
fn writes_that_fail_end_the_command_with_status_1() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    let d = fresh("full");
    for args in [
        &[
            "solve",
            "--sphere-radius",
            "1e-6",
            "--length",
            "1e-7",
            "--n",
            "32",
            "--modulus",
            "1e9",
            "--load",
            "1e-9",
            "--no-png",
            "--out",
            "s",
        ][..],
        &["solve", "--help"],
        &["stats", sample("di-3.di").as_str()],
        &[
            "theory",
            "hertz",
            "--radius",
            "1e-6",
            "--modulus",
            "1e9",
            "--max-approach",
            "1e-9",
        ],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
            .current_dir(&d)
            .args(args)
            .stdout(std::fs::File::create("/dev/full").unwrap())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn machines_limits_are_estimated_before_allocating() {
    let d = fresh("limits");
    check(
        &d,
        &["bench", "--sizes", "256,10000000"],
        Must::Refuse("a 10000000 x 10000000 bench needs about"),
    );
    check(&d, &["bench", "--sizes", "4"], Must::Refuse("at least 8"));
    check(
        &d,
        &["theory", "maugis", "--tabor", "1", "--points", "100000000000"],
        Must::Refuse("a curve of 100000000000 points needs about"),
    );
    check(
        &d,
        &[
            "--threads",
            "100000",
            "theory",
            "hertz",
            "--radius",
            "1e-6",
            "--modulus",
            "1e9",
            "--max-approach",
            "1e-9",
        ],
        Must::Refuse("--threads must be between 1 and"),
    );
}

#[test]
fn a_mostly_unmeasured_file_is_not_filled_without_being_asked() {
    let d = fresh("unmeasured");
    let frt = sample("frt-1.frt");
    check(
        &d,
        &["stats", &frt, "--fill-unmeasured"],
        Must::Refuse("76456 of 250000 points (30.6 %) are not measured"),
    );
    let o = check(
        &d,
        &["stats", &frt, "--fill-unmeasured", "--max-unmeasured", "1"],
        Must::Succeed,
    );
    assert!(String::from_utf8_lossy(&o.stderr).contains("(30.58 %) were not measured and are filled"));
    check(
        &d,
        &["stats", &frt, "--max-unmeasured", "1"],
        Must::Refuse("applies with fill_unmeasured"),
    );
}

/// A Nanoscope file of one 3 x 2 height image whose Z scale is `z` volts.
fn nanoscope(z: &str) -> Vec<u8> {
    let header = format!(
        "\\*File list\r\n\\*Scanner list\r\n\\@Sens. Zsens: V 10.00 nm/V\r\n\\*Ciao image list\r\n\
         \\Data offset: 1024\r\n\\Data length: 12\r\n\\Bytes/pixel: 2\r\n\\Samps/line: 3\r\n\
         \\Number of lines: 2\r\n\\Scan Size: 3 2 ~m\r\n\\@2:Image Data: S [Height] \"Height\"\r\n\
         \\@2:Z scale: V [Sens. Zsens] (0.0001 V/LSB) {z} V\r\n\\*File list end\r\n"
    );
    let mut b = header.into_bytes();
    b.resize(1024, 0);
    b.extend([1i16, 2, 3, 4, 5, 6].iter().flat_map(|v| v.to_le_bytes()));
    b
}

#[test]
fn a_bad_header_number_is_named_by_info_and_stats() {
    let d = fresh("header");
    std::fs::write(d.join("good.di"), nanoscope("6.5536")).unwrap();
    check(&d, &["info", "good.di"], Must::Succeed);
    for (name, z) in [("nan.di", "NaN"), ("zero.di", "0")] {
        std::fs::write(d.join(name), nanoscope(z)).unwrap();
        for cmd in ["info", "stats"] {
            check(
                &d,
                &[cmd, name],
                Must::Refuse("\\@2:Z scale (with its \\@Sens.) is"),
            );
        }
        let o = roughcontact_in(&d, &["info", name]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(!out.contains("inf") && !out.contains("RMS"), "{out}");
    }
}
