//! The guide's reference of case keys is made from the keys' own definitions (their doc
//! comments are the help text), so that it cannot drift from them. `UPDATE_GUIDE=1 cargo test
//! -p runs --test guide` writes it anew after a key changes.

use case::{Case, SolveControl, SweepPath};
use clap::{Args, Command};
use std::path::Path;

/// One table of a group of keys: key, flag, help text (its unit in brackets).
fn table(title: &str, intro: &str, command: Command) -> String {
    let mut out = format!("## {title}\n\n{intro}\n\n| key | flag | meaning |\n|---|---|---|\n");
    for arg in command.get_arguments() {
        let Some(long) = arg.get_long() else { continue };
        let help = arg
            .get_long_help()
            .or(arg.get_help())
            .map(|h| h.to_string())
            .unwrap_or_default()
            .replace('\n', " ")
            .replace('|', "\\|");
        let values = arg
            .get_possible_values()
            .iter()
            .map(|v| match v.get_help() {
                Some(h) => format!("`{}`: {}", v.get_name(), h.to_string().trim_end_matches('.')),
                None => format!("`{}`", v.get_name()),
            })
            .collect::<Vec<_>>();
        let help = match values.as_slice() {
            [] => help,
            [t, f] if t == "`true`" && f == "`false`" => format!("{help}; a switch (`true` or `false`)"),
            _ => format!("{help}; one of {}", values.join("; ")),
        };
        out += &format!("| `{}` | `--{long}` | {help} |\n", arg.get_id());
    }
    out
}

fn page() -> String {
    let mut page = String::from(
        "# Case keys\n\n\
         Every key of a TOML case file is also a flag of `roughcontact solve` and `sweep` (in \
         kebab-case) and a keyword of the Python package (`from` is `from_` there). Flags \
         override the file; a key the case would not use is refused with the reason. Units \
         stand in brackets. This page is made from the keys' definitions in the `case` crate \
         (`UPDATE_GUIDE=1 cargo test -p runs --test guide`).\n\n",
    );
    page += &table(
        "The case",
        "Geometry, material, adhesion and solver settings, for `solve` and `sweep` alike.",
        Case::augment_args(Command::new("case")),
    );
    page += "\n";
    page += &table(
        "A single solve",
        "Exactly one control, for `solve`.",
        SolveControl::augment_args(Command::new("solve")),
    );
    page += "\n";
    page += &table(
        "A sweep's path",
        "A cycle (`from`, `to`, `steps`) or a list of controls, for `sweep`.",
        SweepPath::augment_args(Command::new("sweep")),
    );
    page
}

#[test]
fn the_guides_case_keys_are_the_keys_definitions() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/reference/case-keys.md");
    let made = page();
    if std::env::var_os("UPDATE_GUIDE").is_some() {
        std::fs::write(&path, &made).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == made,
        "docs/reference/case-keys.md is not what the keys say; run UPDATE_GUIDE=1 cargo test -p runs --test guide"
    );
}
