//! The README as a test: its spec blocks compile (or fail with the message
//! shown after them), every `lpm` command in its `sh` blocks runs with the
//! status it says, the first command prints the output shown, the synopsis
//! names only flags `lpm` has, and the test command is what CI runs. (Its
//! Rust blocks are doctests of the `lagrangian` crate.)
#![cfg(unix)] // the scratch folders link `specs` with a symbolic link

mod common;

use common::{ROOT, stderr, stdout};
use lagrangian_core::Compiled;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fenced block of the README: its info string, its text and the line
/// of its opening fence.
struct Block {
    info: String,
    text: String,
    line: usize,
}

fn readme() -> String {
    std::fs::read_to_string(Path::new(ROOT).join("README.md")).unwrap()
}

fn blocks(readme: &str) -> Vec<Block> {
    let mut blocks = Vec::new();
    let mut open: Option<Block> = None;
    for (k, line) in readme.lines().enumerate() {
        match (&mut open, line.strip_prefix("```")) {
            (None, Some(info)) => {
                open = Some(Block {
                    info: info.trim().to_string(),
                    text: String::new(),
                    line: k + 1,
                })
            }
            (Some(_), Some("")) => blocks.extend(open.take()),
            (Some(block), _) => {
                block.text.push_str(line);
                block.text.push('\n');
            }
            (None, None) => {}
        }
    }
    assert!(open.is_none(), "an unclosed code block");
    blocks
}

/// The commands of a `sh` block: continuation lines joined, comment lines
/// dropped, each with the comment at its end (if any).
fn commands(block: &Block) -> Vec<(String, String)> {
    let joined = block.text.replace("\\\n", " ");
    joined
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty() && !line.starts_with('#'))
        .map(|line| match line.split_once(" #") {
            Some((command, comment)) => (command.trim().to_string(), comment.trim().to_string()),
            None => (line.to_string(), String::new()),
        })
        .collect()
}

/// A fresh folder with `specs` linked to the workspace's, where commands
/// write what they write.
fn workspace(name: &str) -> PathBuf {
    let dir = common::temporary(&format!("readme-{name}"));
    std::os::unix::fs::symlink(Path::new(ROOT).join("specs"), dir.join("specs")).unwrap();
    dir
}

/// Runs a README command line as a shell would split it (quotes, `$VAR`),
/// with `lpm` the binary under test, in `dir`.
fn run(line: &str, dir: &Path) -> Output {
    let words = shell_words(line);
    assert_eq!(words[0], "lpm", "not an lpm command: {line}");
    Command::new(env!("CARGO_BIN_EXE_lpm"))
        .args(&words[1..])
        .current_dir(dir)
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_TASK_MIN", "1")
        .env("SLURM_ARRAY_TASK_COUNT", "16")
        .output()
        .expect("lpm runs")
}

/// `line` split into words: single quotes keep their text, `$NAME` is the
/// environment variable of the test's choice (only `SLURM_ARRAY_TASK_ID`:
/// the first task of a 16-task Slurm array).
fn shell_words(line: &str) -> Vec<String> {
    let line = line.replace("$SLURM_ARRAY_TASK_ID", "1");
    let mut words = Vec::new();
    let mut word = String::new();
    let mut quoted = false;
    for c in line.chars() {
        match c {
            '\'' => quoted = !quoted,
            ' ' if !quoted => {
                if !word.is_empty() {
                    words.push(std::mem::take(&mut word));
                }
            }
            c => word.push(c),
        }
    }
    if !word.is_empty() {
        words.push(word);
    }
    words
}

/// The exit status a command's comment states (`# exit status 5: …`), else 0.
fn expected_status(comment: &str) -> i32 {
    comment
        .strip_prefix("exit status ")
        .and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|digits| digits.parse().ok())
        .unwrap_or(0)
}

#[test]
fn the_test_command_is_what_ci_runs_and_the_first_command_prints_what_is_shown() {
    let readme = readme();
    let blocks = blocks(&readme);
    let first = &blocks[0];
    assert_eq!(first.info, "sh");
    let lines: Vec<&str> = first.text.lines().collect();
    let ci = std::fs::read_to_string(Path::new(ROOT).join(".ci/run")).unwrap();
    assert_eq!(
        ci.lines().last(),
        Some(lines[1]),
        "README line {}",
        first.line
    );
    let simulate = lines[0]
        .strip_prefix("cargo run --release -p lpm -- ")
        .expect("the first command runs lpm");
    let dir = workspace("first");
    let out = run(&format!("lpm {simulate}"), &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let shown = &blocks[1];
    assert_eq!(shown.info, "text");
    assert_eq!(stdout(&out), shown.text, "README line {}", shown.line);
}

#[test]
fn every_spec_compiles_or_fails_with_the_message_shown_after_it() {
    let readme = readme();
    let blocks = blocks(&readme);
    let mut specs = 0;
    for (k, block) in blocks.iter().enumerate() {
        if block.info != "rust,ignore" {
            continue;
        }
        specs += 1;
        match Compiled::from_source(&block.text) {
            Ok(compiled) => {
                let file = Path::new(ROOT)
                    .join(format!("specs/{}.lpm", compiled.model.name.to_lowercase()));
                if let Ok(shipped) = std::fs::read_to_string(&file) {
                    assert_eq!(
                        block.text, shipped,
                        "README line {} vs {file:?}",
                        block.line
                    );
                }
            }
            Err(errors) => {
                let name = block.text.split_whitespace().nth(1).unwrap_or("spec");
                let file = format!("{}.lpm", name.trim_end_matches(';').to_lowercase());
                let shown = &blocks[k + 1];
                assert_eq!(shown.info, "text", "README line {}", block.line);
                assert_eq!(
                    errors.render(&file, &block.text),
                    shown.text,
                    "README line {}",
                    shown.line
                );
            }
        }
    }
    assert!(specs >= 3, "{specs} spec blocks");
}

#[test]
fn every_command_runs_with_the_status_it_states() {
    let readme = readme();
    let dir = workspace("commands");
    let mut count = 0;
    for block in blocks(&readme).iter().skip(1).filter(|b| b.info == "sh") {
        for (command, comment) in commands(block) {
            let out = run(&command, &dir);
            count += 1;
            assert_eq!(
                out.status.code(),
                Some(expected_status(&comment)),
                "README line {}: {command}\n{}",
                block.line,
                stderr(&out)
            );
        }
    }
    assert!(count >= 10, "{count} commands");
}

#[test]
fn the_synopsis_names_only_flags_lpm_has() {
    let readme = readme();
    let blocks = blocks(&readme);
    let synopsis = blocks
        .iter()
        .find(|b| b.info == "text" && b.text.starts_with("lpm "))
        .expect("a synopsis of the subcommands");
    for line in synopsis.text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let help = Command::new(env!("CARGO_BIN_EXE_lpm"))
            .args([words[1], "--help"])
            .output()
            .unwrap();
        assert!(help.status.success(), "lpm {} --help", words[1]);
        let help = stdout(&help);
        for word in &words[2..] {
            let flag = word.trim_start_matches(['[', '(']);
            if let Some(flag) = flag.strip_prefix("--") {
                let flag = flag.split([' ', '=', ']', ')']).next().unwrap_or(flag);
                assert!(
                    help.contains(&format!("--{flag}")),
                    "`lpm {}` has no --{flag}",
                    words[1]
                );
            }
        }
    }
}

#[test]
fn the_dependency_snippet_names_the_crate_and_its_features() {
    let readme = readme();
    let manifest: toml::Table = std::fs::read_to_string(Path::new(ROOT).join("Cargo.toml"))
        .unwrap()
        .parse()
        .unwrap();
    let features = manifest["features"].as_table().unwrap();
    for block in blocks(&readme).iter().filter(|b| b.info == "toml") {
        let uncommented: String = block
            .text
            .lines()
            .map(|l| l.trim_start_matches("# "))
            .filter(|l| l.starts_with("lagrangian") || l.starts_with('['))
            .map(|l| format!("{}\n", l.replace("lagrangian =", "x =")))
            .collect();
        for line in uncommented.lines().filter(|l| l.starts_with("x =")) {
            let table: toml::Table = line.parse().unwrap();
            let dependency = table["x"].as_table().unwrap();
            for key in dependency.keys() {
                assert!(
                    ["path", "default-features", "features"].contains(&key.as_str()),
                    "{key}"
                );
            }
            for feature in dependency
                .get("features")
                .and_then(|f| f.as_array())
                .into_iter()
                .flatten()
            {
                assert!(features.contains_key(feature.as_str().unwrap()));
            }
        }
    }
    assert_eq!(manifest["package"]["name"].as_str(), Some("lagrangian"));
    assert!(features.contains_key("sim"));
}

#[test]
fn every_excerpt_is_in_the_file_it_names() {
    let readme = readme();
    let mut count = 0;
    for block in blocks(&readme) {
        let mut lines = block.text.lines();
        let first = lines.next().unwrap_or("");
        let Some(path) = (first.strip_prefix("// ").or(first.strip_prefix("# ")))
            .and_then(|l| l.strip_suffix(" (excerpt)"))
        else {
            continue;
        };
        let file = std::fs::read_to_string(Path::new(ROOT).join(path)).unwrap();
        let excerpt: String = lines.map(|l| format!("{l}\n")).collect();
        assert!(
            file.contains(&excerpt),
            "README line {}: the excerpt is not in {path}:\n{excerpt}",
            block.line
        );
        count += 1;
    }
    assert!(count >= 2, "{count} excerpts");
}

#[test]
fn the_scenario_section_list_names_every_simulation_key() {
    // The keys as the scenario reader knows them: a misspelt key lists them.
    let dir = workspace("simulation-keys");
    let out = run(
        "lpm simulate specs/yaris_double_pendulum.lpm --set simulation.no_such_key=1 --out o",
        &dir,
    );
    let message = stderr(&out);
    let list = message
        .split_once("expected one of ")
        .unwrap_or_else(|| panic!("{message}"))
        .1;
    let keys: Vec<&str> = list.lines().next().unwrap().split(", ").collect();
    assert!(keys.len() >= 10, "{keys:?}");
    let readme = readme();
    let bullet = readme
        .split_once("* `[simulation]`: ")
        .and_then(|(_, rest)| rest.split_once("\n* "))
        .expect("the README's `[simulation]` bullet")
        .0;
    for key in keys {
        assert!(
            bullet.contains(key),
            "the README's [simulation] list lacks {key}"
        );
    }
}
