//! The README and the book (`docs/book/**/*.md`) as a test: every fenced
//! block is checked or carries a `skip: REASON` marker in its info string
//! (the number of skipped blocks is held here, so none slips in). Spec
//! blocks compile (or fail with the message shown after them), every `lpm`
//! command in a `sh` block runs with the status it states, the README's
//! first command prints the output shown, the synopsis names only flags
//! `lpm` has, excerpts are in the files they name, links point at files
//! that exist, and the test command is what CI runs. Rust blocks are
//! doctests of the `lagrangian` crate; Python blocks are run by
//! `python/tests/test_readme.py`.
#![cfg(unix)] // the scratch folders link `specs` with a symbolic link

mod common;

use common::{ROOT, stderr, stdout};
use lagrangian_core::Compiled;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The blocks marked `skip: REASON`, each a `file: reason` line. A new one
/// must be added here, so that a block that stops being run is a decision.
const SKIPPED: &[&str] = &[
    "README.md: the equations of motion, not code",
    "README.md: installs from the Python registry; python/test.sh does it",
    "docs/book/fmu.md: builds a crate (minutes); python/tests/test_fmu_compiled.py runs it",
];

/// A markdown file of the README or the book, by its path from the root.
struct Document {
    path: String,
    text: String,
}

/// A fenced block of a document: its info string, its text and the line
/// of its opening fence.
struct Block {
    info: String,
    text: String,
    line: usize,
}

impl Block {
    /// The block's language: the info string's first word.
    fn language(&self) -> &str {
        self.info.split([' ', ',']).next().unwrap_or("")
    }

    /// The reason given by a `skip: REASON` marker, if the block has one.
    fn skipped(&self) -> Option<&str> {
        self.info
            .split_once(" skip: ")
            .map(|(_, reason)| reason.trim())
    }
}

fn read(path: &str) -> String {
    std::fs::read_to_string(Path::new(ROOT).join(path)).unwrap()
}

fn readme() -> String {
    read("README.md")
}

/// The README, then every markdown file under `docs/book/`, in path order.
fn documents() -> Vec<Document> {
    let mut paths = Vec::new();
    markdown_files(&Path::new(ROOT).join("docs/book"), &mut paths);
    paths.sort();
    let book = paths.into_iter().map(|p| {
        let relative = p.strip_prefix(ROOT).unwrap().to_string_lossy();
        relative.trim_start_matches('/').to_string()
    });
    std::iter::once("README.md".to_string())
        .chain(book)
        .map(|path| Document {
            text: read(&path),
            path,
        })
        .collect()
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            markdown_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}

fn blocks(readme: &str) -> Vec<Block> {
    let mut blocks = Vec::new();
    let mut open: Option<Block> = None;
    for (k, line) in readme.lines().enumerate() {
        assert!(
            line.starts_with("```") || !line.trim_start().starts_with("```"),
            "line {}: an indented fence (this test reads top-level blocks only)",
            k + 1
        );
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

/// What checks a block, by its kind.
#[derive(Debug, PartialEq)]
enum Check {
    /// `sh`: each `lpm` command runs with the status it states.
    Commands,
    /// `rust,ignore`: a spec that compiles, or fails as the next block shows.
    Spec,
    /// `text` after a spec that fails: the message it gives.
    Diagnostic,
    /// `text` after the README's first command: what it prints.
    Output,
    /// `rust`: a doctest of the `lagrangian` crate.
    Doctest,
    /// `python`: run by `python/tests/test_readme.py`.
    Python,
    /// `toml` or `text` whose first line names a file and `(excerpt)`.
    Excerpt,
    /// `toml`: the dependency snippet.
    Dependency,
    /// `text` of `lpm` lines: the synopsis of the subcommands.
    Synopsis,
    /// `… skip: REASON`: not run, for the reason given.
    Skipped,
}

/// The file an excerpt block names on its first line (`// PATH (excerpt)`
/// or `# PATH (excerpt)`), if it is one.
fn excerpt_of(block: &Block) -> Option<&str> {
    let first = block.text.lines().next().unwrap_or("");
    first
        .strip_prefix("// ")
        .or(first.strip_prefix("# "))
        .and_then(|l| l.strip_suffix(" (excerpt)"))
}

/// How `blocks[k]` of `document` is checked, or `None` for a block nothing
/// checks (which the test refuses).
fn check(document: &Document, blocks: &[Block], k: usize) -> Option<Check> {
    let block = &blocks[k];
    let after_failing_spec = || {
        k > 0
            && blocks[k - 1].info == "rust,ignore"
            && Compiled::from_source(&blocks[k - 1].text).is_err()
    };
    if block.skipped().is_some() {
        return Some(Check::Skipped);
    }
    Some(match block.info.as_str() {
        "sh" => Check::Commands,
        "rust,ignore" => Check::Spec,
        "rust" => Check::Doctest,
        "python" => Check::Python,
        _ if excerpt_of(block).is_some() => Check::Excerpt,
        "toml" => Check::Dependency,
        "text" if document.path == "README.md" && k == 1 => Check::Output,
        "text" if after_failing_spec() => Check::Diagnostic,
        "text" if block.text.lines().all(|l| l.starts_with("lpm ")) => Check::Synopsis,
        _ => return None,
    })
}

#[test]
fn every_block_is_checked_or_skipped_with_a_reason() {
    let doctests = read("src/lib.rs");
    let python = read("python/tests/test_readme.py");
    let mut skipped = Vec::new();
    let mut counts = std::collections::BTreeMap::new();
    for document in documents() {
        let blocks = blocks(&document.text);
        for (k, block) in blocks.iter().enumerate() {
            let check = check(&document, &blocks, k).unwrap_or_else(|| {
                panic!(
                    "{} line {}: a ```{} block that no test checks; \
                     mark it `{} skip: REASON` and list it in SKIPPED",
                    document.path,
                    block.line,
                    block.info,
                    block.language()
                )
            });
            match check {
                Check::Skipped => {
                    let reason = block.skipped().unwrap();
                    assert!(!reason.is_empty(), "{} line {}", document.path, block.line);
                    skipped.push(format!("{}: {reason}", document.path));
                }
                Check::Doctest => {
                    let include = format!("include_str!(\"../{}\")", document.path);
                    assert!(
                        doctests.contains(&include),
                        "{} has Rust blocks: src/lib.rs must make them doctests ({include})",
                        document.path
                    );
                }
                Check::Python => {
                    let root = document.path.split('/').next().unwrap();
                    assert!(
                        python.contains(&format!("\"{root}\"")),
                        "test_readme.py does not read {}",
                        document.path
                    );
                }
                _ => {}
            }
            *counts.entry(format!("{check:?}")).or_insert(0) += 1;
        }
    }
    eprintln!("blocks by check: {counts:?}");
    assert_eq!(skipped, SKIPPED, "the skipped blocks");
}

#[test]
fn every_spec_compiles_or_fails_with_the_message_shown_after_it() {
    let mut specs = 0;
    for document in documents() {
        let blocks = blocks(&document.text);
        for (k, block) in blocks.iter().enumerate() {
            if block.info != "rust,ignore" {
                continue;
            }
            specs += 1;
            let at = format!("{} line {}", document.path, block.line);
            match Compiled::from_source(&block.text) {
                Ok(compiled) => {
                    let file = Path::new(ROOT)
                        .join(format!("specs/{}.lpm", compiled.model.name.to_lowercase()));
                    if let Ok(shipped) = std::fs::read_to_string(&file) {
                        assert_eq!(block.text, shipped, "{at} vs {file:?}");
                    }
                }
                Err(errors) => {
                    let name = block.text.split_whitespace().nth(1).unwrap_or("spec");
                    let file = format!("{}.lpm", name.trim_end_matches(';').to_lowercase());
                    let shown = blocks.get(k + 1).expect("the message after a failing spec");
                    assert_eq!(shown.info, "text", "{at}");
                    assert_eq!(errors.render(&file, &block.text), shown.text, "{at}");
                }
            }
        }
    }
    assert!(specs >= 3, "{specs} spec blocks");
}

/// The `sh` commands of `document`, run in a folder of its own; how many.
fn run_commands(document: &Document, k: usize) -> usize {
    let dir = workspace(&format!("commands-{k}"));
    let mut count = 0;
    let blocks = blocks(&document.text);
    // The README's first block is cargo's (the previous test runs it).
    let skip = usize::from(document.path == "README.md");
    for block in blocks.iter().skip(skip).filter(|b| b.info == "sh") {
        for (command, comment) in commands(block) {
            let out = run(&command, &dir);
            count += 1;
            assert_eq!(
                out.status.code(),
                Some(expected_status(&comment)),
                "{} line {}: {command}\n{}",
                document.path,
                block.line,
                stderr(&out)
            );
        }
    }
    count
}

#[test]
fn every_command_runs_with_the_status_it_states() {
    let documents = documents();
    // One thread a document: its commands in order, the documents side by side.
    let count: usize = std::thread::scope(|scope| {
        let runs: Vec<_> = documents
            .iter()
            .enumerate()
            .map(|(k, document)| scope.spawn(move || run_commands(document, k)))
            .collect();
        runs.into_iter().map(|r| r.join().unwrap()).sum()
    });
    assert!(count >= 30, "{count} commands");
}

/// The document holding the fenced block that `found` picks.
fn find_block(found: impl Fn(&Block) -> bool) -> (String, Block) {
    documents()
        .into_iter()
        .find_map(|d| {
            let path = d.path.clone();
            blocks(&d.text).into_iter().find(&found).map(|b| (path, b))
        })
        .expect("the block")
}

#[test]
fn the_synopsis_names_only_flags_lpm_has() {
    let (_, synopsis) = find_block(|b| b.info == "text" && b.text.starts_with("lpm "));
    let mut subcommands = Vec::new();
    for line in synopsis.text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        subcommands.push(words[1].to_string());
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
    // And every subcommand `lpm --help` lists is in it.
    let help = stdout(
        &Command::new(env!("CARGO_BIN_EXE_lpm"))
            .arg("--help")
            .output()
            .unwrap(),
    );
    let listed = help
        .split_once("Commands:")
        .expect("lpm --help lists its commands")
        .1
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help");
    for name in listed {
        assert!(
            subcommands.iter().any(|s| s == name),
            "the synopsis lacks `lpm {name}`"
        );
    }
}

#[test]
fn the_dependency_snippet_names_the_crate_and_its_features() {
    let manifest: toml::Table = read("Cargo.toml").parse().unwrap();
    let features = manifest["features"].as_table().unwrap();
    let mut snippets = 0;
    for document in documents() {
        for block in blocks(&document.text) {
            if block.info != "toml" || excerpt_of(&block).is_some() {
                continue;
            }
            snippets += 1;
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
    }
    assert!(snippets >= 1, "no dependency snippet");
    assert_eq!(manifest["package"]["name"].as_str(), Some("lagrangian"));
    assert!(features.contains_key("sim"));
}

#[test]
fn every_excerpt_is_in_the_file_it_names() {
    let mut count = 0;
    for document in documents() {
        for block in blocks(&document.text) {
            let Some(path) = excerpt_of(&block) else {
                continue;
            };
            let file = read(path);
            let excerpt: String = block
                .text
                .lines()
                .skip(1)
                .map(|l| format!("{l}\n"))
                .collect();
            assert!(
                file.contains(&excerpt),
                "{} line {}: the excerpt is not in {path}:\n{excerpt}",
                document.path,
                block.line
            );
            count += 1;
        }
    }
    assert!(count >= 4, "{count} excerpts");
}

/// A heading's anchor as GitHub and mdBook make it: lower case, spaces to
/// `-`, punctuation other than `-` and `_` dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || [' ', '-', '_'].contains(c))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a markdown text's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut found = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            found.push(anchor(line.trim_start_matches('#')));
        }
    }
    found
}

/// The targets of a markdown text's inline links `[…](target)`, outside
/// code spans and blocks.
fn links(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut found = Vec::new();
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let prose: String = line.split('`').step_by(2).collect::<Vec<_>>().join("");
        for (_, rest) in prose
            .match_indices("](")
            .map(|(i, _)| prose.split_at(i + 2))
        {
            if let Some(end) = rest.find(')') {
                found.push(rest[..end].to_string());
            }
        }
    }
    found
}

#[test]
fn every_link_names_a_file_and_heading_that_exist() {
    let mut count = 0;
    for document in documents().into_iter().chain(
        [
            "ARCHITECTURE.md",
            "BENCHMARKS.md",
            "docs/benchmarks-history.md",
        ]
        .map(|path| Document {
            path: path.to_string(),
            text: read(path),
        }),
    ) {
        let dir = Path::new(&document.path).parent().unwrap().to_path_buf();
        for target in links(&document.text) {
            if target.starts_with("http") {
                continue;
            }
            let (file, heading) = target.split_once('#').unwrap_or((&target, ""));
            let file = if file.is_empty() {
                PathBuf::from(&document.path)
            } else {
                dir.join(file)
            };
            let path = Path::new(ROOT).join(&file);
            assert!(
                path.exists(),
                "{}: a link to {target}, which is not there",
                document.path
            );
            if !heading.is_empty() {
                let text = std::fs::read_to_string(&path).unwrap();
                assert!(
                    anchors(&text).iter().any(|a| a == heading),
                    "{}: {target} names no heading of {file:?}",
                    document.path
                );
            }
            count += 1;
        }
    }
    assert!(count >= 40, "{count} links");
}

#[test]
fn the_book_lists_every_chapter() {
    let summary = read("docs/book/SUMMARY.md");
    let listed = links(&summary);
    for document in documents().into_iter().skip(1) {
        let chapter = document.path.trim_start_matches("docs/book/");
        if chapter != "SUMMARY.md" {
            assert!(
                listed.iter().any(|l| l == chapter),
                "SUMMARY.md lacks {chapter}"
            );
        }
    }
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
    let reference = read("docs/book/reference/scenario-keys.md");
    let bullet = reference
        .split_once("* `[simulation]`: ")
        .and_then(|(_, rest)| rest.split_once("\n* "))
        .expect("the reference's `[simulation]` bullet")
        .0;
    for key in keys {
        assert!(
            bullet.contains(key),
            "the scenario reference's [simulation] list lacks {key}"
        );
    }
}
