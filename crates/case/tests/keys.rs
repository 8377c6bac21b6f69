//! Any keys, any values, any types, any combination, through the entry point the command line,
//! the Python package and a study's runs share (`from_table`, `fill_defaults`, `build`, the
//! control): each case either builds a problem whose record (the resolved case) holds every
//! value given as given, or is refused with an error that names a key; never a panic.

use case::{Case, SolveControl, from_table, to_toml};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;

/// Every key of a solve's case.
fn all_keys() -> Vec<String> {
    let mut keys = Vec::new();
    // The keys as serde names them (every field, `None` ones included).
    for v in [
        serde_json::to_value(Case::default()).unwrap(),
        serde_json::to_value(SolveControl::default()).unwrap(),
    ] {
        keys.extend(v.as_object().unwrap().keys().cloned());
    }
    keys.retain(|k| k != "out");
    keys
}

/// Any TOML value, the awkward ones and the plausible ones often.
fn value() -> impl Strategy<Value = toml::Value> {
    let number = prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-1.0),
        Just(0.0),
        Just(1e300),
        Just(1e-9),
        Just(1e-6),
        Just(1e9),
        Just(0.5),
        -10.0..10.0f64,
        any::<f64>(),
    ];
    let leaf = prop_oneof![
        number.prop_map(toml::Value::Float),
        prop_oneof![
            Just(0i64),
            Just(-3),
            Just(1),
            Just(16),
            Just(32),
            Just(i64::MAX),
            Just(i64::MIN),
            0..64i64
        ]
        .prop_map(toml::Value::Integer),
        prop_oneof![
            Just("surface"),
            Just("none"),
            Just("exponential"),
            Just("periodic"),
            Just("free"),
            Just("flow"),
            Just("no/such/file.npy"),
            Just(""),
            Just("1e-6"),
        ]
        .prop_map(|s| toml::Value::String(s.to_string())),
        any::<bool>().prop_map(toml::Value::Boolean),
    ];
    leaf.prop_recursive(1, 4, 3, |inner| {
        prop::collection::vec(inner, 0..3).prop_map(toml::Value::Array)
    })
}

/// A case: a few plausible keys that make a problem (so that building is reached), and any
/// keys with any values laid over them.
fn case() -> impl Strategy<Value = toml::Table> {
    let keys = all_keys();
    let base = prop_oneof![
        Just(vec![
            ("modulus", toml::Value::Float(1e9)),
            ("length", toml::Value::Float(1e-7)),
            ("n", toml::Value::Integer(16)),
            ("sphere_radius", toml::Value::Float(1e-6)),
            ("approach", toml::Value::Float(1e-9))
        ]),
        Just(vec![
            ("modulus", toml::Value::Float(1e9)),
            ("length", toml::Value::Float(1e-6)),
            ("n", toml::Value::Integer(16)),
            ("rms_height", toml::Value::Float(1e-8)),
            ("mean_pressure", toml::Value::Float(1e6))
        ]),
        Just(vec![]),
    ];
    let n = keys.len();
    (base, prop::collection::vec((0..n, value()), 0..4)).prop_map(move |(base, extra)| {
        let mut t = toml::Table::new();
        for (k, v) in base {
            t.insert(k.to_string(), v);
        }
        for (i, v) in extra {
            t.insert(keys[i].clone(), v);
        }
        t
    })
}

/// Whether `message` names a key of the case (snake_case or as a flag).
fn names_a_key(message: &str, keys: &[String]) -> bool {
    keys.iter().any(|k| {
        message.contains(&format!("`{k}`"))
            || message.contains(&format!("--{}", k.replace('_', "-")))
            || message.contains(&format!("{k} "))
            || message.contains(&format!("{k} ="))
    })
}

/// Two values equal as a key records them (an integer given for a number is that number).
fn same(given: &toml::Value, recorded: &toml::Value) -> bool {
    match (given, recorded) {
        (toml::Value::Integer(a), toml::Value::Float(b)) => (*a as f64) == *b,
        (toml::Value::Array(a), toml::Value::Array(b)) => {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| same(x, y))
        }
        _ => given == recorded,
    }
}

fn judge(table: toml::Table) -> Result<(), TestCaseError> {
    let keys = all_keys();
    let given = table.clone();
    let outcome = std::panic::catch_unwind(|| -> case::Result<String> {
        let (mut case, control): (Case, SolveControl) = from_table("the keys", table)?;
        case.fill_defaults("run/solve");
        let built = case.build()?;
        control.control(&built.problem)?;
        case.validate_settings(built.problem.adhesive())?;
        to_toml(&case, &control)
    });
    let Ok(outcome) = outcome else {
        return Err(TestCaseError::fail(format!("panicked on {given}")));
    };
    match outcome {
        Ok(record) => {
            let record: toml::Table = toml::from_str(&record).unwrap();
            for (k, v) in &given {
                let recorded = record.get(k);
                prop_assert!(
                    recorded.is_some_and(|r| same(v, r)),
                    "`{k}` = {v} was given, the record says {recorded:?}"
                );
            }
        }
        Err(e) => {
            let message = format!("{e:#}");
            prop_assert!(
                names_a_key(&message, &keys),
                "the error names no key: {message}\n(case: {given})"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn any_case_builds_as_recorded_or_is_refused_naming_a_key(table in case()) {
        judge(table)?;
    }
}
