//! `lpm sweep`: the runs it makes, its tables, shards, and its errors.

mod common;

use common::{ROOT, lpm, stderr, temporary};
use std::process::Command;

use std::path::PathBuf;

const SCENARIO: &str = "specs/scenarios/yaris_full_frontal.toml";

/// The rows of a CSV file as maps from column to cell.
fn read_csv(path: &PathBuf) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_string)
        .collect();
    let rows = reader
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn cell<'a>(header: &[String], row: &'a [String], name: &str) -> &'a str {
    let k = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    &row[k]
}

/// Short runs (20 ms of the crash) keep the test fast.
const SHORT: [&str; 2] = ["--set", "simulation.t_end=0.02"];

#[test]
fn grid_runs_every_combination_and_matches_lpm_simulate() {
    let dir = temporary("grid");
    let out = dir.join("grid.csv");
    let status = lpm(&[
        &["sweep", SCENARIO, "--quiet", "--out", out.to_str().unwrap()][..],
        &SHORT,
        &[
            "--grid",
            "initial.velocities.r=-12,-15.5556",
            "--grid",
            "components.front_end.stiffness_values*=0.5:1.5:3",
        ],
    ]
    .concat());
    assert!(status.status.success(), "{}", stderr(&status));
    let (header, rows) = read_csv(&out);
    assert_eq!(rows.len(), 6);
    assert_eq!(
        &header[..5],
        [
            "run",
            "initial.velocities.r",
            "components.front_end.stiffness_values*",
            "status",
            "error"
        ]
    );
    let factors: Vec<&str> = rows
        .iter()
        .map(|r| cell(&header, r, "components.front_end.stiffness_values*"))
        .collect();
    assert_eq!(factors, ["0.5", "1.0", "1.5", "0.5", "1.0", "1.5"]);
    // A stiffer front end crushes less.
    let crush: Vec<f64> = rows
        .iter()
        .map(|r| cell(&header, r, "max_crush_m").parse().unwrap())
        .collect();
    assert!(crush[0] > crush[1] && crush[1] > crush[2], "{crush:?}");
    // Run 5 is `lpm simulate` with the stiffness values scaled by 1.5 by hand.
    let single = dir.join("single");
    let scaled = "components.front_end.stiffness_values=[3.6e6, 3.6e6, 3.15e6, 1.41e6, 0.8505e6, 0.75e6, 0.84375e6]";
    let simulated = lpm(&[
        &[
            "simulate",
            "specs/yaris_double_pendulum.lpm",
            "--out",
            single.to_str().unwrap(),
        ][..],
        &SHORT,
        &["--set", scaled, "--set", "initial.velocities.r=-15.5556"],
    ]
    .concat());
    assert!(simulated.status.success(), "{}", stderr(&simulated));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(single.join("summary.json")).unwrap())
            .unwrap();
    for metric in [
        "max_crush_m",
        "peak_deceleration_g",
        "max_theta1_deg",
        "rhs_evaluations",
    ] {
        let ours: f64 = cell(&header, &rows[5], metric).parse().unwrap();
        let theirs = summary[metric].as_f64().unwrap();
        assert!(
            (ours - theirs).abs() <= 1e-12 * theirs.abs(),
            "{metric}: {ours} vs {theirs}"
        );
    }
}

#[test]
fn shards_concatenate_to_the_full_sweep() {
    let dir = temporary("shards");
    let design = [
        "--samples",
        "7",
        "--vary",
        "k1=5e4:1e5",
        "--vary",
        "components.weld.failure_moment=2e3:8e3:log",
        "--seed",
        "11",
        "--quiet",
    ];
    let run = |out: &PathBuf, extra: &[&str]| {
        let o = lpm(&[
            &["sweep", SCENARIO, "--out", out.to_str().unwrap()][..],
            &SHORT,
            &design,
            extra,
        ]
        .concat());
        assert!(o.status.success(), "{}", stderr(&o));
    };
    let full = dir.join("full.csv");
    run(&full, &["--threads", "2"]);
    let mut joined = Vec::new();
    for i in 1..=3 {
        let part = dir.join(format!("part{i}.csv"));
        run(&part, &["--shard", &format!("{i}/3"), "--threads", "1"]);
        let (header, rows) = read_csv(&part);
        joined.push((header, rows));
    }
    let (header, rows) = read_csv(&full);
    assert_eq!(rows.len(), 7);
    assert!(joined.iter().all(|(h, _)| *h == header));
    let concatenated: Vec<Vec<String>> = joined.into_iter().flat_map(|(_, r)| r).collect();
    assert_eq!(concatenated, rows);
    // The Parquet table holds the same rows.
    let parquet = dir.join("full.parquet");
    run(&parquet, &[]);
    let bytes = std::fs::read(&parquet).unwrap();
    assert_eq!(&bytes[..4], b"PAR1");
    assert_eq!(&bytes[bytes.len() - 4..], b"PAR1");
}

#[test]
fn a_failed_run_is_a_row_not_the_end_of_the_sweep() {
    let dir = temporary("failed");
    let out = dir.join("f.csv");
    let o = lpm(&[
        &["sweep", SCENARIO, "--quiet", "--out", out.to_str().unwrap()][..],
        &SHORT,
        &["--grid", "simulation.max_steps=3,100000"],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("1 failed"));
    let (header, rows) = read_csv(&out);
    assert_eq!(cell(&header, &rows[0], "status"), "max_steps");
    assert!(cell(&header, &rows[0], "error").contains("more than 3 steps"));
    assert_eq!(cell(&header, &rows[0], "max_crush_m"), "");
    assert_eq!(cell(&header, &rows[1], "status"), "ok");
}

/// Every run failing is status 18, and the table still records each failure.
#[test]
fn a_sweep_where_every_run_fails_exits_with_status_18() {
    let dir = temporary("all-failed");
    let out = dir.join("f.csv");
    let o = lpm(&[
        &["sweep", SCENARIO, "--quiet", "--out", out.to_str().unwrap()][..],
        &SHORT,
        &["--grid", "simulation.max_steps=2,3"],
    ]
    .concat());
    assert_eq!(o.status.code(), Some(18), "{}", stderr(&o));
    let message = stderr(&o);
    assert!(
        message.starts_with("error: every run failed\n2 runs"),
        "{message}"
    );
    assert!(
        message.contains("first failure, run 0: max_steps: integration failed: more than 2 steps"),
        "{message}"
    );
    let (header, rows) = read_csv(&out);
    assert_eq!(rows.len(), 2);
    for row in &rows {
        assert_eq!(cell(&header, row, "status"), "max_steps");
    }
}

#[test]
fn bad_sweeps_are_refused_before_any_run() {
    let dir = temporary("bad");
    let out = dir.join("x.csv");
    let out = out.to_str().unwrap();
    // Keys the scenario does not know: status 4, with a suggestion.
    let cases: [(&[&str], &str); 2] = [
        (
            &["--grid", "kk1=1,2"],
            "`kk1` does not exist in the spec; did you mean `k1`?",
        ),
        (
            &["--grid", "simulation.rtool=1e-6,1e-8"],
            "unknown field `rtool`, expected one of `t_end`, `method`, `rtol`, `atol`, `max_step`, `step`, `output_interval`, `max_steps`, `accelerations`, `time_kinks` (did you mean `rtol`?)",
        ),
    ];
    for (args, expected) in cases {
        let o = lpm(&[&["sweep", SCENARIO, "--quiet", "--out", out][..], args].concat());
        assert_eq!(o.status.code(), Some(4), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{args:?}: {}", stderr(&o));
    }
    let cases: [(&[&str], &str); 6] = [
        (
            &["--grid", "components.front_end.unloading*=2,3"],
            "a factor scales a number, or a list or table of numbers, not `\"plastic\"`",
        ),
        (
            &["--grid", "k1=1,2", "--set", "k1=3"],
            "both swept and fixed",
        ),
        (
            &["--grid", "k1=1,2", "--samples", "3", "--vary", "k2=1:2"],
            "cannot be used with",
        ),
        (&["--samples", "3"], "--vary"),
        (&["--grid", "k1=1,2", "--shard", "4/3"], "4/3"),
        (&["--grid", "k1=1,2,x"], "`x` is not a number"),
    ];
    for (args, expected) in cases {
        let o = lpm(&[&["sweep", SCENARIO, "--quiet", "--out", out][..], args].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{args:?}: {}", stderr(&o));
    }
    let o = lpm(&["sweep", SCENARIO, "--grid", "k1=1,2", "--out", "x.txt"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains(".csv or .parquet"), "{}", stderr(&o));
    assert!(
        !dir.join("x.csv").exists(),
        "nothing is written when the sweep is refused"
    );
}

/// The arguments of a sweep long enough to interrupt (the full 150 ms crash).
fn long_sweep(out: &std::path::Path, runs: usize) -> Vec<String> {
    [
        "sweep",
        SCENARIO,
        "--quiet",
        "--threads",
        "2",
        "--grid",
        &format!("k1=20000:80000:{runs}"),
        "--out",
        out.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

#[test]
fn a_journal_cut_anywhere_resumes_to_the_uninterrupted_table() {
    let dir = temporary("resume");
    let full = dir.join("full.csv");
    let o = lpm(&long_sweep(&full, 40));
    assert!(o.status.success(), "{}", stderr(&o));
    let complete = std::fs::read_to_string(&full).unwrap();
    // What a kill leaves: the header, some rows, half of the next row.
    let out = dir.join("cut.csv");
    let journal = dir.join("cut.csv.partial");
    let lines: Vec<&str> = complete.split_inclusive('\n').collect();
    let mut cut: String = lines[..14].concat();
    cut.push_str(&lines[14][..lines[14].len() / 2]);
    std::fs::write(&journal, &cut).unwrap();
    // Without --resume the journal is not overwritten.
    let refused = lpm(&long_sweep(&out, 40));
    assert_eq!(refused.status.code(), Some(2));
    assert!(
        stderr(&refused).contains("--resume"),
        "{}",
        stderr(&refused)
    );
    assert_eq!(std::fs::read_to_string(&journal).unwrap(), cut);
    let mut resume = long_sweep(&out, 40);
    resume.push("--resume".into());
    let o = lpm(&resume);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("(13 from the journal, 27 now)"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), complete);
    assert!(!journal.exists());
    // Nothing left to resume.
    let o = lpm(&resume);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("is complete"), "{}", stderr(&o));
}

#[test]
fn a_journal_of_another_sweep_is_not_resumed() {
    let dir = temporary("other");
    let first = dir.join("a.csv");
    assert!(lpm(&long_sweep(&first, 6)).status.success());
    let text = std::fs::read_to_string(&first).unwrap();
    let out = dir.join("b.csv");
    std::fs::write(dir.join("b.csv.partial"), &text).unwrap();
    // Same columns, other values (7 runs instead of 6 along k1).
    let mut resume = long_sweep(&out, 7);
    resume.push("--resume".into());
    let o = lpm(&resume);
    assert_eq!(o.status.code(), Some(7), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("b.csv.partial:3: run 1 with values [32000.0] is not run 1 of this sweep (values [30000.0])"),
        "{}",
        stderr(&o)
    );
}

#[cfg(unix)]
#[test]
fn sigterm_stops_a_sweep_that_resume_then_finishes() {
    let dir = temporary("sigterm");
    let full = dir.join("full.csv");
    let out = dir.join("stopped.csv");
    let journal = dir.join("stopped.csv.partial");
    let args = long_sweep(&out, 600);
    let child = Command::new(env!("CARGO_BIN_EXE_lpm"))
        .args(&args)
        .current_dir(ROOT)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Wait for some rows, then ask it to stop as `kill` does.
    let rows = || std::fs::read_to_string(&journal).map_or(0, |t| t.lines().count());
    let start = std::time::Instant::now();
    while rows() < 20 && start.elapsed().as_secs() < 120 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let o = child.wait_with_output().unwrap();
    if o.status.success() {
        // It finished before the signal arrived: nothing to test on this host.
        return;
    }
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    assert!(stderr(&o).contains("--resume"), "{}", stderr(&o));
    assert!(!out.exists(), "no half table under the output's name");
    let kept = rows() - 1;
    assert!((19..600).contains(&kept), "{kept} rows kept");
    let mut resume = args.clone();
    resume.push("--resume".into());
    let o = lpm(&resume);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(lpm(&long_sweep(&full, 600)).status.success());
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        std::fs::read_to_string(&full).unwrap()
    );
}
