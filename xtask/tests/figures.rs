//! Quick mode end to end: every figure is drawn (PNG + SVG), FIGURES.md is written, and the
//! numbers behind each figure are held as insta snapshots, rounded to three significant
//! digits so that only a change of physics (not round-off) shows as a snapshot diff.

use xtask::{ALL, Options, Table, figures};

/// At most `rows` evenly spaced rows of `t`, each number to three digits; numbers below 1e-6
/// of their column's largest magnitude print as 0.
fn digest(t: &Table, rows: usize) -> String {
    let columns = t.columns.len();
    let scale: Vec<f64> = (0..columns)
        .map(|c| t.rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max))
        .collect();
    let step = t.rows.len().div_ceil(rows).max(1);
    let mut s = t.columns.join(",") + "\n";
    for r in t.rows.iter().step_by(step) {
        let cells: Vec<String> = r
            .iter()
            .zip(&scale)
            .map(|(&v, &m)| {
                if v.abs() <= 1e-6 * m {
                    "0".into()
                } else {
                    format!("{v:.2e}")
                }
            })
            .collect();
        s += &(cells.join(",") + "\n");
    }
    s
}

#[test]
fn quick_mode_regenerates_every_figure() {
    let out = std::env::temp_dir().join(format!("xtask-figures-{}", std::process::id()));
    let reports = rayon::ThreadPoolBuilder::new()
        .build()
        .unwrap()
        .install(|| {
            figures(Options {
                quick: true,
                only: Vec::new(),
                out: out.clone(),
                challenge_surface: None,
                fresh: true,
                progress: false,
                rough_law: case::LawKind::Point,
                challenge_law: case::LawKind::Surface,
            })
        })
        .unwrap();
    assert_eq!(reports.iter().map(|r| r.number).collect::<Vec<_>>(), ALL.to_vec());
    let markdown = std::fs::read_to_string(out.join("FIGURES.md")).unwrap();
    for r in &reports {
        assert!(
            !r.agreement.is_empty(),
            "figure {} reports no agreement",
            r.number
        );
        assert!(markdown.contains(&format!("## Figure {}:", r.number)));
        for img in &r.images {
            for ext in ["png", "svg"] {
                let f = out.join(format!("{img}.{ext}"));
                assert!(
                    std::fs::metadata(&f).map(|m| m.len() > 1000).unwrap_or(false),
                    "{}",
                    f.display()
                );
            }
        }
        // Every unconverged row of a figure whose rows are its plotted points is drawn hollow.
        if [5, 6, 11, 12, 13, 14].contains(&r.number) {
            let t = &r.tables[0];
            let c = t
                .columns
                .iter()
                .position(|c| c == "converged" || c == "all_converged")
                .unwrap();
            let failed = t.rows.iter().filter(|row| row[c] == 0.0).count();
            assert_eq!(r.unconverged_points, failed, "figure {}", r.number);
        }
        for t in &r.tables {
            assert!(out.join(format!("{}.csv", t.name)).exists());
            // Greenwood's curves are snapshotted by the theory crate's own tests.
            if !t.name.ends_with("_greenwood") {
                insta::assert_snapshot!(t.name.clone(), digest(t, 40));
            }
        }
    }
    // Reusing the cache: a second build computes nothing and gives the same tables.
    let again = figures(Options {
        quick: true,
        only: vec![8],
        out: out.clone(),
        challenge_surface: None,
        fresh: false,
        progress: false,
        rough_law: case::LawKind::Point,
        challenge_law: case::LawKind::Surface,
    })
    .unwrap();
    let first = reports.iter().find(|r| r.number == 8).unwrap();
    // As CSV: a table's missing values are NaN, which no `==` matches.
    let csv = |r: &xtask::FigureReport| r.tables.iter().map(|t| t.csv()).collect::<Vec<_>>();
    assert_eq!(csv(&again[0]), csv(first));
    std::fs::remove_dir_all(&out).ok();
}
