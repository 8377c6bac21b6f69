//! The committed benchmark cases (`data/bench/*.toml`, the sweeps among them) stay cases the
//! command line accepts: every key known and typed, the settings and the path valid, the
//! problem built (its surface generated). A benchmark that no longer parses measures nothing.

use case::{Case, SweepPath, layered};
use std::path::Path;

#[test]
fn every_committed_sweep_case_builds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/bench");
    let mut sweeps = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let table: toml::Table = toml::from_str(&text).unwrap();
        if table.contains_key("command") {
            continue; // a study's file (`roughcontact study`), read by the cli's own tests
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let (mut case, mut sweep): (Case, SweepPath) =
            layered(Some((&name, &text)), &Case::default(), &SweepPath::default())
                .unwrap_or_else(|e| panic!("{e:#}"));
        case.fill_defaults("run/sweep");
        sweep.fill_defaults();
        case.validate_settings(case.adhesive())
            .unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let controls = sweep.controls().unwrap_or_else(|e| panic!("{name}: {e:#}"));
        assert!(!controls.is_empty(), "{name}");
        case.build().unwrap_or_else(|e| panic!("{name}: {e:#}"));
        sweeps.push(name);
    }
    sweeps.sort();
    assert_eq!(
        sweeps,
        [
            "challenge-surface-1024.toml",
            "challenge-surface-4096.toml",
            "rough-sphere-mu5.toml",
            "sweep-512.toml"
        ]
    );
}
