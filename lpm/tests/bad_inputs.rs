//! The corpus of bad inputs in `tests/bad_inputs/` (specs, scenarios, CSV
//! files): each case of `cases.toml` and of every other `cases_*.toml` there
//! (one file a theme) must fail with its exit status and exactly its message,
//! and write nothing.

mod common;

use common::{ROOT, lpm};

use std::path::Path;

#[test]
fn every_bad_input_gives_its_exact_error_and_writes_nothing() {
    let cases = corpus();
    assert!(cases.len() >= 15, "{} cases", cases.len());
    let mut failures = Vec::new();
    for (k, case) in cases.iter().enumerate() {
        let name = case["name"].as_str().unwrap();
        let out = common::scratch(&format!("bad-{k}"));
        let _ = std::fs::remove_dir_all(&out);
        let args: Vec<String> = case["args"]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_str().unwrap().replace("{out}", out.to_str().unwrap()))
            .collect();
        let o = lpm(&args);
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        let expected_status = case["status"].as_integer().unwrap() as i32;
        let text = |key: &str| {
            case.get(key)
                .and_then(|v| v.as_str())
                .map(|s| s.trim_start_matches('\n'))
        };
        let mut problems = Vec::new();
        if o.status.code() != Some(expected_status) {
            problems.push(format!(
                "status {:?}, expected {expected_status}",
                o.status.code()
            ));
        }
        if let Some(exact) = text("stderr")
            && stderr != exact
        {
            problems.push(format!("stderr differs; expected:\n{exact}"));
        }
        if let Some(start) = text("stderr_starts").map(str::trim_end)
            && !stderr.starts_with(start)
        {
            problems.push(format!("stderr does not start with:\n{start}"));
        }
        if let Some(part) = text("stderr_contains")
            && !stderr.contains(part)
        {
            problems.push(format!("stderr does not contain:\n{part}"));
        }
        if stderr
            .lines()
            .next()
            .is_none_or(|l| !l.starts_with("error: "))
        {
            problems.push("the first line is not an `error: ` message".into());
        }
        let written = std::fs::read_dir(&out).map_or(0, |d| d.count());
        if written > 0 {
            problems.push(format!("{written} files written in {}", out.display()));
        }
        if !problems.is_empty() {
            failures.push(format!(
                "{name} ({args:?}):\n  {}\n  got:\n{stderr}",
                problems.join("\n  ")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The cases of `cases.toml` and of each `cases_*.toml`, in file-name order.
fn corpus() -> Vec<toml::Value> {
    let folder = Path::new(ROOT).join("tests/bad_inputs");
    let mut files: Vec<_> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            name == "cases.toml" || (name.starts_with("cases_") && name.ends_with(".toml"))
        })
        .collect();
    files.sort();
    let mut cases = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let table: toml::Table = text
            .parse()
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let list = table["case"]
            .as_array()
            .unwrap_or_else(|| panic!("{}: no [[case]]", file.display()));
        cases.extend(list.iter().cloned());
    }
    cases
}
