//! Sweeps split over the tasks of a cluster scheduler: `--shard auto`,
//! `--shard-index`/`--shard-count`, `--plan`, and `--merge` of the parts.

mod common;

use common::{ROOT, lpm, stderr, stdout, temporary};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Seven short runs (20 ms of the crash) of the paper scenario over two axes.
const SWEEP: [&str; 12] = [
    "sweep",
    "specs/scenarios/yaris_full_frontal.toml",
    "--set",
    "simulation.t_end=0.02",
    "--samples",
    "7",
    "--vary",
    "k1=5e4:1e5",
    "--vary",
    "components.weld.failure_moment=2e3:8e3:log",
    "--quiet",
    "--threads=1",
];

/// `lpm` on the sweep with `extra` arguments, in an environment holding only
/// `variables` of the schedulers' (and PATH).
fn sweep_with(variables: &[(&str, &str)], extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lpm"))
        .args(SWEEP)
        .args(extra)
        .current_dir(ROOT)
        .env_clear()
        .env("PATH", std::env::var("PATH").unwrap_or_default())
        .envs(variables.iter().copied())
        .output()
        .expect("lpm runs")
}

/// Runs the sweep into `out` and returns the table's bytes.
fn table(variables: &[(&str, &str)], extra: &[&str], out: &Path) -> Vec<u8> {
    let o = sweep_with(
        variables,
        &[extra, &["--out", out.to_str().unwrap()]].concat(),
    );
    assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
    std::fs::read(out).unwrap()
}

fn slurm(id: &str) -> [(&'static str, String); 3] {
    [
        ("SLURM_ARRAY_TASK_ID", id.to_string()),
        ("SLURM_ARRAY_TASK_MIN", "1".to_string()),
        ("SLURM_ARRAY_TASK_COUNT", "3".to_string()),
    ]
}

#[test]
fn scheduler_tasks_make_the_rows_of_the_matching_shard() {
    let dir = temporary("scheduler-shards");
    for i in 1..=3 {
        let by_hand = table(&[], &["--shard", &format!("{i}/3")], &dir.join("hand.csv"));
        let variables = slurm(&i.to_string());
        let variables: Vec<(&str, &str)> =
            variables.iter().map(|(k, v)| (*k, v.as_str())).collect();
        let out = dir.join("slurm.csv");
        assert_eq!(
            table(&variables, &["--shard", "auto"], &out),
            by_hand,
            "Slurm task {i}"
        );
        let k = (i - 1).to_string();
        let kubernetes = [("JOB_COMPLETION_INDEX", k.as_str())];
        let auto = ["--shard", "auto", "--shard-count", "3"];
        let out = dir.join("k8s.csv");
        assert_eq!(
            table(&kubernetes, &auto, &out),
            by_hand,
            "Kubernetes index {k}"
        );
        let aws = [("AWS_BATCH_JOB_ARRAY_INDEX", k.as_str())];
        assert_eq!(
            table(&aws, &auto, &dir.join("aws.csv")),
            by_hand,
            "AWS index {k}"
        );
        let zero_based = ["--shard-index", k.as_str(), "--shard-count", "3"];
        let out = dir.join("condor.csv");
        assert_eq!(table(&[], &zero_based, &out), by_hand, "--shard-index {k}");
    }
}

#[test]
fn shard_auto_outside_a_scheduler_says_what_to_give() {
    let o = sweep_with(&[], &["--shard", "auto", "--out", "never.csv"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(
            "none of SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX, AWS_BATCH_JOB_ARRAY_INDEX is set"
        ),
        "{}",
        stderr(&o)
    );
    let kubernetes = [("JOB_COMPLETION_INDEX", "1")];
    let o = sweep_with(&kubernetes, &["--shard", "auto", "--out", "never.csv"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--shard-count N"), "{}", stderr(&o));
    let o = sweep_with(
        &[],
        &["--shard-index", "3", "--shard-count", "3", "--out", "x.csv"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("shard index 3 is not below the shard count 3"),
        "{}",
        stderr(&o)
    );
    assert!(!Path::new(ROOT).join("never.csv").exists());
}

/// The three shards' tables, the first two as CSV and the last as Parquet.
fn parts(dir: &Path) -> Vec<PathBuf> {
    let names = ["part1.csv", "part2.csv", "part3.parquet"];
    (1..=3)
        .zip(names)
        .map(|(i, name)| {
            let part = dir.join(name);
            table(&[], &["--shard", &format!("{i}/3")], &part);
            part
        })
        .collect()
}

fn merge(parts: &[&PathBuf], out: &Path) -> Output {
    let mut args: Vec<&str> = vec!["--merge"];
    args.extend(parts.iter().map(|p| p.to_str().unwrap()));
    args.extend(["--out", out.to_str().unwrap()]);
    sweep_with(&[], &args)
}

#[test]
fn merged_shards_are_one_full_run_byte_for_byte() {
    let dir = temporary("merge");
    let parts = parts(&dir);
    for full in ["full.csv", "full.parquet"] {
        let whole = table(&[], &[], &dir.join(full));
        let merged = dir.join(format!("merged-{full}"));
        // In any order.
        let o = merge(&[&parts[2], &parts[0], &parts[1]], &merged);
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(
            stdout(&o),
            format!("merged 7 runs from 3 parts into {}\n", merged.display())
        );
        assert!(std::fs::read(&merged).unwrap() == whole, "{full}");
    }
}

#[test]
fn merge_refuses_missing_repeated_and_foreign_parts_and_writes_nothing() {
    let dir = temporary("merge-refused");
    let parts = parts(&dir);
    let out = dir.join("merged.csv");
    let refused = |o: Output, expected: &str| {
        assert_eq!(o.status.code(), Some(7), "{}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{expected}: {}", stderr(&o));
        assert!(!out.exists());
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().flatten().collect();
        assert_eq!(left.len(), 3, "a temporary file is left: {left:?}");
    };
    let missing = merge(&[&parts[0], &parts[2]], &out);
    refused(
        missing,
        "part3.parquet: row 1: runs 2..4 are missing (of 7)",
    );
    let last = merge(&[&parts[0], &parts[1]], &out);
    refused(last, "runs 4..7 are missing (of 7)");
    let twice = merge(&[&parts[0], &parts[1], &parts[1], &parts[2]], &out);
    refused(twice, "part2.csv:2: run 2 is repeated");
    // The same parts against another plan (another seed).
    let mut foreign: Vec<&str> = vec!["--seed", "12", "--merge"];
    foreign.extend(parts.iter().map(|p| p.to_str().unwrap()));
    foreign.extend(["--out", out.to_str().unwrap()]);
    refused(
        sweep_with(&[], &foreign),
        "part1.csv:2: run 0 has the values",
    );
    // A table of other columns.
    let other = temporary("merge-other").join("other.csv");
    std::fs::write(&other, "run,k,status\n0,1.0,ok\n").unwrap();
    refused(
        merge(&[&other], &out),
        "other.csv: the columns are not those of this sweep",
    );
}

#[test]
fn plan_counts_the_runs_and_suggests_a_split() {
    let o = sweep_with(&[], &["--plan"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(
        text.starts_with("7 runs over k1, components.weld.failure_moment\n"),
        "{text}"
    );
    assert!(text.contains("(7 timed)"), "{text}");
    assert!(text.contains("suggested split: none"), "{text}");
    let o = lpm(&[
        "sweep",
        "specs/scenarios/yaris_full_frontal.toml",
        "--grid",
        "k1=5e4:1e5:10000",
        "--grid",
        "components.weld.failure_moment=2e3:8e3:10000",
        "--set",
        "simulation.t_end=0.02",
        "--plan",
    ]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    let tasks: usize = text
        .split("--shard-count ")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no split in {text}"));
    // ten minutes of one core per task: 1e8 runs of at least 10 µs each.
    assert!(tasks >= 2, "{text}");
    assert!(text.contains(&format!("Slurm --array=1-{tasks}")), "{text}");
}

#[test]
fn the_slurm_templates_run_a_sweep_whose_merge_is_one_full_run() {
    let results = temporary("slurm-template");
    let bin = Path::new(env!("CARGO_BIN_EXE_lpm")).parent().unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let script = |name: &str, task: &str| {
        let o = Command::new("bash")
            .arg(format!("docs/clusters/{name}"))
            .current_dir(ROOT)
            .env("PATH", &path)
            .env("SLURM_SUBMIT_DIR", ROOT)
            .env("SLURM_ARRAY_TASK_ID", task)
            .env("SLURM_ARRAY_TASK_MIN", "1")
            .env("SLURM_ARRAY_TASK_COUNT", "3")
            .env("SAMPLES", "5")
            .env("RESULTS", &results)
            .output()
            .unwrap();
        assert!(o.status.success(), "{name} {task}: {}", stderr(&o));
    };
    for task in ["1", "2", "3"] {
        script("slurm_sweep.sh", task);
    }
    script("slurm_merge.sh", "");
    let full = results.join("full.parquet");
    let o = lpm(&[
        "sweep",
        "specs/scenarios/yaris_full_frontal.toml",
        "--samples",
        "5",
        "--vary",
        "k1=5e4:1e5",
        "--vary",
        "components.weld.failure_moment=2e3:8e3:log",
        "--seed",
        "1",
        "--quiet",
        "--out",
        full.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let merged = std::fs::read(results.join("sweep.parquet")).unwrap();
    assert!(merged == std::fs::read(&full).unwrap());
}
