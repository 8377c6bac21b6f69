use super::plan::*;
use super::table::*;
use super::*;

fn study(text: &str) -> Result<Study> {
    Study::parse(text, Path::new("/studies/s.toml"))
}

/// A run under way shows its finished steps and, once its sweep has written it, where its
/// running step stands; a finished step clears that.
#[test]
fn runs_under_way_show_where_their_step_stands() {
    let runs = std::env::temp_dir().join(format!("roughcontact-standing-{}", std::process::id()));
    let dir = crate::run::RunDir::open(&runs.join("a"), crate::run::Reuse::Refuse).unwrap();
    std::fs::write(dir.path().join("curve.csv"), "step\n0\n1\n").unwrap();
    assert_eq!(standing(&runs, &["a"]), "a (2 steps done)");
    dir.write_progress(Some("step 3/11: iteration 40, residual 1.00e-2"));
    assert_eq!(
        standing(&runs, &["a"]),
        "a (2 steps done; step 3/11: iteration 40, residual 1.00e-2)"
    );
    dir.write_progress(None);
    assert_eq!(standing(&runs, &["a"]), "a (2 steps done)");
    drop(dir);
    std::fs::remove_dir_all(&runs).unwrap();
}

#[test]
fn wall_times_read_with_their_units() {
    for (text, seconds) in [("90", 90.0), ("90s", 90.0), ("30m", 1800.0), ("1.5h", 5400.0)] {
        assert_eq!(
            parse_duration(text),
            Ok(Duration::from_secs_f64(seconds)),
            "{text}"
        );
    }
    for bad in ["", "h", "-1m", "2d", "inf", "1 hour"] {
        assert!(parse_duration(bad).is_err(), "{bad}");
    }
}

#[test]
fn axes_expand_into_named_runs() {
    let s = study(
        "command = \"sweep\"\ncase = { modulus = 1e9, rms_height = 1e-8, start_from = \"a\" }\n[axes]\nseed = [1, 2]\nlaw = [\"point\", \"surface\"]\n",
    )
    .unwrap();
    let names: Vec<&str> = s.runs.iter().map(|r| r.name.as_str()).collect();
    // The axes in alphabetical order, the last varying fastest.
    let expected = [
        "law=point_seed=1",
        "law=point_seed=2",
        "law=surface_seed=1",
        "law=surface_seed=2",
    ];
    assert_eq!(names, expected);
    assert_eq!(s.case["start_from"].as_str(), Some("/studies/a"));
    let zipped =
        study("command = \"solve\"\ncombine = \"zip\"\ncase = { rms_height = 1e-8, law = \"point\" }\n[axes]\nseed = [1, 2]\nz0 = [1e-9, 2e-9]\n")
            .unwrap();
    assert_eq!(zipped.runs.len(), 2);
    assert_eq!(zipped.runs[1].name, "seed=2_z0=2e-9");
}

#[test]
fn bad_studies_are_refused() {
    for (text, message) in [
        ("[axes]\nseed = [1]\n", "command = \"solve\" or \"sweep\""),
        ("command = \"run\"\n", "`command` is"),
        ("command = \"solve\"\n[axes]\nseed = 1\n", "non-empty list"),
        ("command = \"solve\"\n[axes]\nseed = []\n", "non-empty list"),
        (
            "command = \"solve\"\ncombine = \"zip\"\n[axes]\nseed = [1, 2]\nz0 = [1.0]\n",
            "one length",
        ),
        (
            "command = \"solve\"\n[axes]\nseed = [1, 1]\n",
            "share the directory",
        ),
        ("command = \"solve\"\nbogus = 1\n", "unknown key `bogus`"),
    ] {
        let e = format!("{:#}", study(text).unwrap_err());
        assert!(e.contains(message), "{text}: {e}");
    }
    assert!(parse_shard("0/2").is_err() && parse_shard("3/2").is_err() && parse_shard("x").is_err());
    assert_eq!(parse_shard("2/3").unwrap(), (2, 3));
}

/// Any value an axis could list, the plausible and the awkward.
fn axis_value() -> impl proptest::strategy::Strategy<Value = toml::Value> {
    use proptest::prelude::*;
    prop_oneof![
        prop_oneof![
            Just(f64::NAN),
            Just(-1.0),
            Just(0.0),
            Just(1e-9),
            Just(0.5),
            Just(48.5),
            any::<f64>()
        ]
        .prop_map(toml::Value::Float),
        prop_oneof![Just(-3i64), Just(0), Just(1), Just(32), Just(i64::MAX)].prop_map(toml::Value::Integer),
        prop_oneof![Just("two"), Just("point"), Just("free"), Just("")]
            .prop_map(|s| toml::Value::String(s.into())),
        any::<bool>().prop_map(toml::Value::Boolean),
        Just(toml::Value::Array(vec![toml::Value::Integer(1)])),
    ]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 200, failure_persistence: None, ..Default::default() })]

    /// Any axes over a generated surface's case: the study is refused naming an axis or a
    /// key, or every run's case reads, types and applies (so no run fails on them).
    #[test]
    fn any_axes_are_checked_before_a_run(
        axes in proptest::collection::vec(
            (proptest::sample::select(vec!["seed", "n", "hurst", "law", "z0", "modulus", "exact_sphere", "surface", "bogus", "mean_pressure", "tolerance", "domain"]),
             proptest::collection::vec(axis_value(), 1..3)),
            1..3,
        ),
        command in proptest::sample::select(vec!["solve", "sweep"]),
    ) {
        let mut text = format!("command = \"{command}\"\n[case]\nlength = 1e-6\nrms_height = 1e-8\nmodulus = 1e9\n[axes]\n");
        let mut seen = Vec::new();
        for (k, values) in &axes {
            if seen.contains(k) {
                continue;
            }
            seen.push(*k);
            text += &format!("{k} = {}\n", toml::Value::Array(values.clone()));
        }
        let parsed = std::panic::catch_unwind(|| study(&text));
        proptest::prop_assert!(parsed.is_ok(), "panicked on {text}");
        match parsed.unwrap() {
            Ok(s) => {
                for run in &s.runs {
                    let mut t = s.case.clone();
                    t.extend(run.values.iter().cloned());
                    let read = if command == "sweep" {
                        case::from_table::<case::Case, case::SweepPath>("run", t).map(|(c, _)| c)
                    } else {
                        case::from_table::<case::Case, case::SolveControl>("run", t).map(|(c, _)| c)
                    };
                    let applies = read.and_then(|mut c| {
                        c.fill_defaults("");
                        c.check_applicable()
                    });
                    proptest::prop_assert!(applies.is_ok(), "{text}: run {} passed the check: {:?}", run.name, applies.err());
                }
            }
            Err(e) => {
                let message = format!("{e:#}");
                proptest::prop_assert!(
                    seen.iter().any(|k| message.contains(&format!("`{k}`")) || message.contains(&format!("--{}", k.replace('_', "-")))),
                    "{text}: the error names no axis: {message}"
                );
            }
        }
    }
}

#[test]
fn groups_have_means_and_standard_errors() {
    let s = study(
        "command = \"solve\"\ncase = { rms_height = 1e-8 }\n[axes]\nmodulus = [1, 2]\nseed = [1, 2, 3]\n",
    )
    .unwrap();
    let table = "run,modulus,seed,status,error,load,law\n\
                 a,1,1,finished,,1.0,x\na,1,2,finished,,2.0,x\na,1,3,finished,,3.0,x\n\
                 b,2,1,finished,,5.0,x\nb,2,2,failed,\"bad, input\",,\nb,2,3,finished,,7.0,x\n";
    let g = group(table, &s, "seed").unwrap();
    let lines: Vec<&str> = g.lines().collect();
    assert_eq!(lines[0], "modulus,runs,load_mean,load_stderr,load_count");
    let one: Vec<&str> = lines[1].split(',').collect();
    assert_eq!([one[0], one[1], one[2], one[4]], ["1", "3", "2e0", "3"]);
    let stderr: f64 = one[3].parse().unwrap();
    assert!((stderr - (1.0f64 / 3.0).sqrt()).abs() < 1e-15, "{stderr}");
    assert_eq!(lines[2], "2,2,6e0,1e0,2");
    let (_, quoted) = read_table("a,b,c\na,\"b, \"\"c\"\"\nd\",e\n").unwrap();
    assert_eq!(quoted, [["a", "b, \"c\"\nd", "e"]]);
}
