//! The architecture page's table of crates and their dependencies is the workspace's: each
//! crate's `[dependencies]` on other workspace crates, read from its `Cargo.toml`.

use std::collections::BTreeMap;
use std::path::Path;

/// Crate name -> the workspace crates it depends on, sorted.
fn from_manifests(root: &Path) -> BTreeMap<String, Vec<String>> {
    let workspace: toml::Table =
        toml::from_str(&std::fs::read_to_string(root.join("Cargo.toml")).unwrap()).unwrap();
    let members: Vec<String> = workspace["workspace"]["members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap().to_string())
        .collect();
    let manifests: Vec<toml::Table> = members
        .iter()
        .map(|m| toml::from_str(&std::fs::read_to_string(root.join(m).join("Cargo.toml")).unwrap()).unwrap())
        .collect();
    let names: Vec<String> = manifests
        .iter()
        .map(|t| t["package"]["name"].as_str().unwrap().to_string())
        .collect();
    manifests
        .iter()
        .zip(&names)
        .map(|(t, name)| {
            let mut deps: Vec<String> = t
                .get("dependencies")
                .and_then(|d| d.as_table())
                .map(|d| d.keys().filter(|k| names.contains(k)).cloned().collect())
                .unwrap_or_default();
            deps.sort();
            (name.clone(), deps)
        })
        .collect()
}

/// The same from the page's table: its first column names the crate, its last the crates it
/// depends on.
fn from_page(page: &str) -> BTreeMap<String, Vec<String>> {
    page.lines()
        .filter(|l| l.starts_with("| `"))
        .map(|l| {
            let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            let name = cells[0].trim_matches('`').to_string();
            let mut deps: Vec<String> = cells[cells.len() - 1]
                .split(',')
                .map(|d| d.trim().trim_matches('`').to_string())
                .filter(|d| !d.is_empty())
                .collect();
            deps.sort();
            (name, deps)
        })
        .collect()
}

/// Each crate's floor in the page's drawing: the lines `floor N   crate (what) ...`.
fn floors(page: &str, crates: &[String]) -> BTreeMap<String, usize> {
    page.lines()
        .filter_map(|l| l.strip_prefix("floor "))
        .flat_map(|l| {
            let mut words = l.split_whitespace();
            let floor: usize = words.next().unwrap().parse().unwrap();
            words
                .filter(|w| crates.contains(&w.to_string()))
                .map(move |w| (w.to_string(), floor))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn the_architecture_page_draws_the_workspaces_dependencies() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let page = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let manifests = from_manifests(&root);
    assert_eq!(
        from_page(&page),
        manifests,
        "docs/architecture.md's table against the Cargo.toml files"
    );
    let names: Vec<String> = manifests.keys().cloned().collect();
    let floor = floors(&page, &names);
    for (name, deps) in &manifests {
        let own = floor
            .get(name)
            .unwrap_or_else(|| panic!("{name} is on no floor of the drawing"));
        for d in deps {
            assert!(
                floor[d] < *own,
                "{name} (floor {own}) uses {d} (floor {}), not below it",
                floor[d]
            );
        }
    }
}
