//! `roughcontact study`: the same table whether the runs go one by one, two at a time or in
//! shards merged afterwards, and after a kill and a resumption; a failed run is recorded and
//! the others finish.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

const STUDY: &str = r#"command = "sweep"

# A rough sphere (Rq = 0.3 z0) on 32^2 cells, a short cycle.
[case]
sphere_radius = 1e-6
n = 32
length = 3e-7
modulus = 1e9
z0 = 1e-9
rms_height = 3e-10
from = -2e-9
to = 1e-9
steps = 3

[axes]
seed = [1, 2, 3]
# Tabor parameters 1.36 and 2.15; -1 is refused by validation.
work_of_adhesion = [0.05, 0.1, -1.0]
"#;

fn roughcontact(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(args)
        .output()
        .expect("runs")
}

fn fresh(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("study.toml"), STUDY).unwrap();
    dir
}

fn study(dir: &Path, extra: &[&str]) -> Output {
    let file = dir.join("study.toml");
    let out = dir.join("study");
    let mut args = vec!["study", file.to_str().unwrap(), "--out", out.to_str().unwrap()];
    args.extend(extra);
    let o = roughcontact(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn tables(dir: &Path) -> (String, String) {
    let read = |f: &str| std::fs::read_to_string(dir.join("study").join(f)).unwrap();
    (read("study.csv"), read("study-groups.csv"))
}

#[test]
fn serial_parallel_sharded_and_resumed_studies_give_the_same_tables() {
    let serial = fresh("study-serial");
    let o = study(&serial, &[]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.contains("9 runs: 6 finished, 3 failed, 0 not run"), "{said}");
    let (table, groups) = tables(&serial);
    let rows: Vec<&str> = table.lines().collect();
    assert_eq!(rows.len(), 10);
    assert!(
        rows[0].starts_with("run,seed,work_of_adhesion,status,error,"),
        "{}",
        rows[0]
    );
    assert!(rows[0].contains(",pull_off_force,") && !rows[0].contains("wall_time"));
    let failed: Vec<&&str> = rows.iter().filter(|r| r.contains(",failed,")).collect();
    assert_eq!(failed.len(), 3);
    assert!(
        failed
            .iter()
            .all(|r| r.contains("work_of_adhesion = -1.0: must be finite and > 0"))
    );
    // One group per Tabor parameter, three seeds each.
    let g: Vec<&str> = groups.lines().collect();
    assert_eq!(g.len(), 3, "{groups}");
    assert!(
        g[0].starts_with("work_of_adhesion,runs,")
            && g[1].starts_with("0.05,3,")
            && g[2].starts_with("0.1,3,")
    );

    let parallel = fresh("study-parallel");
    study(&parallel, &["--jobs", "2"]);
    assert_eq!(tables(&parallel), (table.clone(), groups.clone()));

    let sharded = fresh("study-sharded");
    let o = study(&sharded, &["--shard", "1/2"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("not run"));
    study(&sharded, &["--shard", "2/2"]);
    study(&sharded, &["--merge"]);
    assert_eq!(tables(&sharded), (table.clone(), groups.clone()));

    // Killed once two runs have finished, then run again: the finished runs are kept and a
    // half-finished sweep resumes.
    let killed = fresh("study-killed");
    let file = killed.join("study.toml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(["study", file.to_str().unwrap(), "--out"])
        .arg(killed.join("study"))
        .spawn()
        .unwrap();
    let runs = killed.join("study").join("runs");
    let started = Instant::now();
    let finished = || {
        std::fs::read_dir(&runs)
            .map(|d| {
                d.filter(|e| e.as_ref().unwrap().path().join("summary.json").exists())
                    .count()
            })
            .unwrap_or(0)
    };
    while finished() < 2 && started.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let before = finished();
    assert!(
        (2..6).contains(&before),
        "{before} runs had finished when the study was killed"
    );
    // A copy of its small files only (as a repository keeps them), one run cut to a sweep
    // halfway: the unfinished runs start over.
    let copied = fresh("study-copied");
    copy_without_states(&killed.join("study"), &copied.join("study"));
    let half = copied.join("study/runs/seed=1_work_of_adhesion=0.05");
    std::fs::remove_file(half.join("summary.json")).unwrap();
    let curve = std::fs::read_to_string(half.join("curve.csv")).unwrap();
    let rows: String = curve.split_inclusive('\n').take(3).collect();
    std::fs::write(half.join("curve.csv"), rows).unwrap();
    study(&killed, &[]);
    assert_eq!(tables(&killed), (table.clone(), groups.clone()));
    let kept = copied.join("study/runs/seed=1_work_of_adhesion=0.1/summary.json");
    let before = std::fs::metadata(&kept).unwrap().modified().unwrap();
    study(&copied, &[]);
    assert_eq!(tables(&copied), (table, groups));
    // Its finished runs were kept, though their directory moved.
    assert_eq!(std::fs::metadata(&kept).unwrap().modified().unwrap(), before);
}

#[test]
fn a_finished_run_whose_case_changed_is_solved_again() {
    let changed = fresh("study-changed");
    study(&changed, &[]);
    let original = tables(&changed);
    let edited = STUDY.replace("to = 1e-9", "to = 1.5e-9");
    assert_ne!(edited, STUDY);
    std::fs::write(changed.join("study.toml"), &edited).unwrap();
    study(&changed, &[]);
    let direct = fresh("study-changed-direct");
    std::fs::write(direct.join("study.toml"), &edited).unwrap();
    study(&direct, &[]);
    assert_eq!(tables(&changed), tables(&direct));
    assert_ne!(tables(&changed), original);
}

fn copy_without_states(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap();
        if ["state", "state.new", "state.old", "states", ".lock"]
            .iter()
            .any(|s| name == *s)
        {
            continue;
        }
        if path.is_dir() {
            copy_without_states(&path, &to.join(name));
        } else {
            std::fs::copy(&path, to.join(name)).unwrap();
        }
    }
}

#[test]
fn no_run_starts_after_the_time_given() {
    let dir = fresh("study-start-within");
    let o = study(&dir, &["--start-within", "0m"]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        said.contains("9 runs: 0 finished, 0 failed, 9 not run (none started after --start-within 0s"),
        "{said}"
    );
    let started = std::fs::read_dir(dir.join("study").join("runs")).map_or(0, |d| d.count());
    assert_eq!(started, 0);
    let (table, _) = tables(&dir);
    assert_eq!(table.lines().filter(|r| r.contains(",not run,")).count(), 9);
}

#[test]
fn bad_study_arguments_are_refused() {
    let dir = fresh("study-bad");
    let file = dir.join("study.toml");
    let f = file.to_str().unwrap();
    for (args, message) in [
        (vec!["study", f, "--jobs", "0"], "--jobs must be between 1 and"),
        (vec!["study", f, "--shard", "3/2"], "--shard is I/N"),
        (
            vec!["study", f, "--start-within", "2d"],
            "`2d` is not a wall time",
        ),
        (
            vec!["study", f, "--merge", "--start-within", "1h"],
            "--merge runs nothing",
        ),
        (
            vec!["study", f, "--group-over", "z0"],
            "no such axis (its axes: seed, work_of_adhesion)",
        ),
        (
            vec!["study", "/nonexistent/study.toml"],
            "reading /nonexistent/study.toml",
        ),
    ] {
        let o = roughcontact(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(message), "{args:?}: {err}");
    }
    let o = roughcontact(&["study", f, "--dry-run"]);
    let listed = String::from_utf8_lossy(&o.stdout);
    assert_eq!(listed.lines().count(), 9);
    assert!(
        listed
            .lines()
            .next()
            .unwrap()
            .ends_with("study/runs/seed=1_work_of_adhesion=0.05")
    );
}

#[test]
fn named_runs_take_their_names_and_wrong_names_are_refused() {
    let dir = fresh("study-names");
    let file = dir.join("study.toml");
    let named = STUDY.replace(
        "[case]",
        "combine = \"zip\"\nnames = [\"first\", \"second\", \"third\"]\n\n[case]",
    );
    std::fs::write(&file, &named).unwrap();
    let o = roughcontact(&["study", file.to_str().unwrap(), "--dry-run"]);
    let listed = String::from_utf8_lossy(&o.stdout);
    let last: Vec<&str> = listed.lines().map(|l| l.rsplit('/').next().unwrap()).collect();
    assert_eq!(
        last,
        ["first", "second", "third"],
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for (names, message) in [
        ("[\"a\", \"b\"]", "2 names for 3 runs"),
        ("[\"a\", \"b/c\", \"d\"]", "not a plain file name"),
        ("[\"a\", \"a\", \"d\"]", "two runs would share the directory a"),
        ("[1, 2, 3]", "`names` are the runs' directory names"),
    ] {
        let text = named.replace("[\"first\", \"second\", \"third\"]", names);
        std::fs::write(&file, text).unwrap();
        let o = roughcontact(&["study", file.to_str().unwrap(), "--dry-run"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(message), "{names}: {err}");
    }
}

/// Under the `mpi` feature (Open MPI installed): `mpirun -n 2` hands the runs to two ranks and
/// gives the serial table.
#[cfg(feature = "mpi")]
#[test]
fn mpirun_gives_the_serial_table() {
    let serial = fresh("study-mpi-serial");
    study(&serial, &[]);
    let ranks = fresh("study-mpi");
    let file = ranks.join("study.toml");
    let o = Command::new("mpirun")
        .args([
            "--allow-run-as-root",
            "--oversubscribe",
            "-n",
            "2",
            env!("CARGO_BIN_EXE_roughcontact"),
        ])
        .args(["study", file.to_str().unwrap(), "--out"])
        .arg(ranks.join("study"))
        .output()
        .expect("mpirun runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let said = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        said.matches("9 runs: 6 finished, 3 failed").count(),
        1,
        "rank 0 alone merges: {said}"
    );
    assert_eq!(tables(&ranks), tables(&serial));
}
