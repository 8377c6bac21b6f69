//! A study's tables: every run's summary merged into `study.csv`, and each group's mean and
//! standard error into `study-groups.csv`.

use anyhow::{Context, Result};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

use super::plan::{Study, spelt};

/// Each of the runs `names` with the steps its curve has so far and where its running step
/// stands.
pub(super) fn standing(runs_dir: &Path, names: &[&str]) -> String {
    names
        .iter()
        .map(|n| {
            let dir = runs_dir.join(n);
            let rows = std::fs::read_to_string(dir.join("curve.csv"))
                .map_or(0, |t| t.lines().count().saturating_sub(1));
            match crate::run::read_progress(&dir) {
                Some(progress) => format!("{n} ({rows} steps done; {})", progress.trim()),
                None => format!("{n} ({rows} steps done)"),
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The finished runs' summaries as one table (study.csv: a row a run in the study's order,
/// its axis values, its status and error, and every number, flag and word of the top level of
/// its summary.json except wall times, so that the table does not depend on how the runs were
/// spread); with the counts of failed and missing runs.
pub(super) fn merge(study: &Study, runs_dir: &Path) -> Result<(String, Counts)> {
    let mut rows: Vec<(String, Option<String>, BTreeMap<String, String>)> = Vec::new();
    let (mut failed, mut missing, mut elsewhere) = (0, 0, 0);
    let mut columns = std::collections::BTreeSet::new();
    for run in &study.runs {
        let dir = runs_dir.join(&run.name);
        let summary = dir.join("summary.json");
        let mut fields = BTreeMap::new();
        let (status, error) = if let Ok(text) = std::fs::read_to_string(&summary) {
            let value: Value =
                serde_json::from_str(&text).with_context(|| format!("reading {}", summary.display()))?;
            if let Value::Object(m) = value {
                for (k, v) in m {
                    let cell = match v {
                        Value::Number(x) => x.to_string(),
                        Value::Bool(b) => b.to_string(),
                        Value::String(s) => s,
                        _ => continue,
                    };
                    if k.ends_with("wall_time_s") {
                        continue;
                    }
                    columns.insert(k.clone());
                    fields.insert(k, cell);
                }
            }
            ("finished".to_string(), None)
        } else if crate::run::busy(&dir) {
            elsewhere += 1;
            ("under way elsewhere".to_string(), None)
        } else if let Ok(e) = std::fs::read_to_string(dir.join("error.txt")) {
            failed += 1;
            ("failed".to_string(), Some(e))
        } else {
            missing += 1;
            ("not run".to_string(), None)
        };
        rows.push((status, error, fields));
    }
    let mut header = vec!["run".to_string()];
    header.extend(study.axes.iter().map(|(k, _)| k.clone()));
    header.extend(["status".to_string(), "error".to_string()]);
    header.extend(columns.iter().cloned());
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(&header)?;
    for (run, (status, error, fields)) in study.runs.iter().zip(rows) {
        let mut record = vec![run.name.clone()];
        record.extend(run.values.iter().map(|(_, v)| spelt(v)));
        record.extend([status, error.unwrap_or_default()]);
        record.extend(columns.iter().map(|c| fields.get(c).cloned().unwrap_or_default()));
        csv.write_record(&record)?;
    }
    let bytes = csv
        .into_inner()
        .map_err(|e| anyhow::anyhow!("writing the table: {e}"))?;
    Ok((
        String::from_utf8(bytes)?,
        Counts {
            failed,
            missing,
            elsewhere,
        },
    ))
}

/// How many runs of a merged table are not finished.
pub(super) struct Counts {
    pub(super) failed: usize,
    pub(super) missing: usize,
    /// Under way in another process (its lock held).
    pub(super) elsewhere: usize,
}

/// A CSV table's header and rows (RFC 4180 quoting: cells may hold commas, quotes and line
/// breaks).
pub(super) fn read_table(table: &str) -> Result<(Vec<String>, Vec<Vec<String>>)> {
    let mut reader = csv::ReaderBuilder::new().from_reader(table.as_bytes());
    let header = reader.headers()?.iter().map(str::to_string).collect();
    let rows = reader
        .records()
        .map(|r| Ok(r?.iter().map(str::to_string).collect()))
        .collect::<Result<_>>()?;
    Ok((header, rows))
}

/// One CSV line of `cells`, quoted where they need it.
pub(super) fn csv_line(cells: &[String]) -> Result<String> {
    let mut csv = csv::WriterBuilder::new().from_writer(Vec::new());
    csv.write_record(cells)?;
    let bytes = csv
        .into_inner()
        .map_err(|e| anyhow::anyhow!("writing the table: {e}"))?;
    Ok(String::from_utf8(bytes)?)
}

/// study-groups.csv: the finished runs grouped by every axis but `over`, and for every
/// numeric column its mean, standard error (sample standard deviation over sqrt(count)) and
/// count over the group.
pub(super) fn group(table: &str, study: &Study, over: &str) -> Result<String> {
    let (header, rows) = read_table(table)?;
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("study.csv has no column `{name}`"))
    };
    let keys: Vec<usize> = study
        .axes
        .iter()
        .filter(|(k, _)| k != over)
        .map(|(k, _)| column(k))
        .collect::<Result<_>>()?;
    let first_result = column("error")? + 1;
    let finished: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[first_result - 2] == "finished")
        .collect();
    let numeric: Vec<usize> = (first_result..header.len())
        .filter(|&c| {
            finished.iter().any(|r| !r[c].is_empty())
                && finished
                    .iter()
                    .all(|r| r[c].is_empty() || r[c].parse::<f64>().is_ok())
        })
        .collect();
    let mut groups: Vec<(Vec<String>, Vec<&Vec<String>>)> = Vec::new();
    for r in &finished {
        let key: Vec<String> = keys.iter().map(|&k| r[k].clone()).collect();
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, members)) => members.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let mut csv = keys.iter().map(|&k| header[k].clone()).collect::<Vec<_>>();
    csv.push("runs".into());
    for &c in &numeric {
        csv.extend([
            format!("{}_mean", header[c]),
            format!("{}_stderr", header[c]),
            format!("{}_count", header[c]),
        ]);
    }
    let mut out = csv_line(&csv)?;
    for (key, members) in groups {
        let mut line: Vec<String> = key;
        line.push(members.len().to_string());
        for &c in &numeric {
            let xs: Vec<f64> = members.iter().filter_map(|r| r[c].parse::<f64>().ok()).collect();
            let n = xs.len() as f64;
            let mean = xs.iter().sum::<f64>() / n;
            let stderr = if xs.len() > 1 {
                (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt() / n.sqrt()
            } else {
                f64::NAN
            };
            line.extend([format!("{mean:e}"), format!("{stderr:e}"), xs.len().to_string()]);
        }
        out += &csv_line(&line)?;
    }
    Ok(out)
}
