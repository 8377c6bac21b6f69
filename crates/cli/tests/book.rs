//! The guide's tutorial pages run as written: every `roughcontact` command in their `sh`
//! blocks succeeds, and every line a `text` block shows is a line the command before it printed.
//! Pages whose commands take minutes (the adhesive sweep, the study) are left to the reader.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The pages tested, under docs/.
const PAGES: [&str; 2] = ["tutorial/first-contact.md", "tutorial/instrument-surface.md"];

/// A page's fenced blocks in order: (language, lines).
fn blocks(page: &str) -> Vec<(String, Vec<String>)> {
    let mut out = Vec::new();
    let mut open: Option<(String, Vec<String>)> = None;
    for line in page.lines() {
        match (&mut open, line.strip_prefix("```")) {
            (None, Some(lang)) => open = Some((lang.trim().to_string(), Vec::new())),
            (Some(_), Some(_)) => out.extend(open.take()),
            (Some((_, lines)), None) => lines.push(line.to_string()),
            (None, None) => {}
        }
    }
    out
}

/// The `roughcontact` commands of an `sh` block, continuation lines joined, comments dropped.
fn commands(lines: &[String]) -> Vec<Vec<String>> {
    let mut joined = Vec::new();
    let mut current = String::new();
    for line in lines {
        let line = line.split(" #").next().unwrap_or("").trim_end();
        match line.strip_suffix('\\') {
            Some(part) => current.push_str(part),
            None => {
                current.push_str(line);
                joined.push(std::mem::take(&mut current));
            }
        }
    }
    joined
        .iter()
        .map(|c| c.split_whitespace().map(str::to_string).collect::<Vec<_>>())
        .filter(|words| words.first().is_some_and(|w| w == "roughcontact"))
        .collect()
}

fn run(words: &[String], work: &Path, root: &Path) -> String {
    let args: Vec<String> = words[1..]
        .iter()
        .map(|a| {
            if a.starts_with("data/") {
                root.join(a).display().to_string()
            } else {
                a.clone()
            }
        })
        .collect();
    let out = Command::new(env!("CARGO_BIN_EXE_roughcontact"))
        .args(&args)
        .current_dir(work)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "`{}` failed:\n{text}", words.join(" "));
    text
}

#[test]
fn the_tutorials_commands_run_and_print_what_the_pages_show() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    for page in PAGES {
        let work = std::env::temp_dir().join(format!(
            "roughcontact-book-{}-{}",
            std::process::id(),
            page.replace('/', "-")
        ));
        let _ = std::fs::remove_dir_all(&work);
        std::fs::create_dir_all(&work).unwrap();
        let text = std::fs::read_to_string(root.join("docs").join(page)).unwrap();
        let mut printed = String::new();
        let mut ran = 0;
        for (lang, lines) in blocks(&text) {
            match lang.as_str() {
                "sh" => {
                    for words in commands(&lines) {
                        printed = run(&words, &work, &root);
                        ran += 1;
                    }
                }
                "text" => {
                    let said: Vec<&str> = printed.lines().map(str::trim).collect();
                    for line in lines.iter().map(|l| l.trim()).filter(|l| !l.is_empty()) {
                        assert!(
                            said.contains(&line),
                            "{page}: `{line}` is not what the command printed:\n{printed}"
                        );
                    }
                }
                _ => {}
            }
        }
        assert!(ran > 0, "{page} has no command");
        let _ = std::fs::remove_dir_all(&work);
    }
}
