//! `lpm sweep --envelope`: envelopes and weighted mean histories, checked
//! against the runs' own trajectories from `lpm simulate`; independent of
//! the number of threads, of the split into shards, of the order of their
//! merge and of a resume; bad weights and other sweeps' partial envelopes
//! refused.

mod common;

use common::{lpm, stderr, stdout, temporary};
use std::path::{Path, PathBuf};

const SCENARIO: &str = "specs/scenarios/yaris_full_frontal.toml";
/// 20 ms of the crash keep the test fast.
const T_END: &str = "simulation.t_end=0.02";
const SPEEDS: [&str; 3] = ["-12", "-15.5556", "-18"];
const WEIGHTS: [f64; 3] = [0.2, 0.5, 0.3];

/// The columns of a CSV file by name.
fn columns(path: &Path) -> Vec<(String, Vec<String>)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    (header.iter().enumerate())
        .map(|(k, name)| {
            (
                name.clone(),
                rows.iter().map(|r| r[k].to_string()).collect(),
            )
        })
        .collect()
}

fn numbers(table: &[(String, Vec<String>)], name: &str) -> Vec<f64> {
    let (_, cells) =
        (table.iter().find(|(n, _)| n == name)).unwrap_or_else(|| panic!("no column {name}"));
    cells.iter().map(|c| c.parse().unwrap()).collect()
}

/// The sweep of the three speeds with the envelopes of `r` and the front
/// end's force, extra arguments appended.
fn sweep(dir: &Path, extra: &[&str]) -> std::process::Output {
    sweep_to(&dir.join("sweep.csv"), extra)
}

/// [`sweep`] with its table written to `out`.
fn sweep_to(out: &Path, extra: &[&str]) -> std::process::Output {
    sweep_of("r,front_end.force", out, extra)
}

/// [`sweep_to`] with the envelopes of `channels`.
fn sweep_of(channels: &str, out: &Path, extra: &[&str]) -> std::process::Output {
    let grid = format!("initial.velocities.r={}", SPEEDS.join(","));
    let args = [
        &[
            "sweep", SCENARIO, "--quiet", "--set", T_END, "--grid", &grid,
        ][..],
        &["--envelope", channels, "--out", out.to_str().unwrap()],
        extra,
    ];
    lpm(&args.concat())
}

/// `lpm simulate` of one speed: its trajectory.csv.
fn trajectory(dir: &Path, speed: &str) -> Vec<(String, Vec<String>)> {
    let out = dir.join(format!("run{speed}"));
    let speed = format!("initial.velocities.r={speed}");
    let o = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--scenario",
        SCENARIO,
        "--set",
        T_END,
        "--set",
        &speed,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    columns(&out.join("trajectory.csv"))
}

/// Checks one channel of the envelope against the runs' histories
/// (trajectory.csv keeps 11 significant digits).
fn check_channel(envelope: &[(String, Vec<String>)], name: &str, runs: &[Vec<f64>]) {
    let scale = runs.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * scale;
    let column = |q: &str| numbers(envelope, &format!("{name}.{q}"));
    let (min, max, mean) = (column("min"), column("max"), column("mean"));
    let (min_run, max_run) = (column("min_run"), column("max_run"));
    assert_eq!(max.len(), runs[0].len(), "{name}: one row per output time");
    for k in 0..max.len() {
        let at: Vec<f64> = runs.iter().map(|run| run[k]).collect();
        let highest = at.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let lowest = at.iter().copied().fold(f64::INFINITY, f64::min);
        let weighted: f64 = at.iter().zip(WEIGHTS).map(|(x, w)| w * x).sum();
        assert!(
            close(max[k], highest),
            "{name} max at {k}: {} vs {highest}",
            max[k]
        );
        assert!(
            close(min[k], lowest),
            "{name} min at {k}: {} vs {lowest}",
            min[k]
        );
        assert!(
            close(at[max_run[k] as usize], highest),
            "{name} max run at {k}"
        );
        assert!(
            close(at[min_run[k] as usize], lowest),
            "{name} min run at {k}"
        );
        assert!(
            close(mean[k], weighted),
            "{name} mean at {k}: {} vs {weighted}",
            mean[k]
        );
    }
}

#[test]
fn the_envelope_is_the_extremes_and_weighted_mean_of_the_runs_trajectories() {
    let dir = temporary("envelope");
    let table = dir.join("envelope.csv");
    let o = sweep(
        &dir,
        &[
            "--weights",
            "initial.velocities.r=0.2,0.5,0.3",
            "--envelope-out",
            table.to_str().unwrap(),
            "--envelope-plot",
            dir.join("envelope.svg").to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let envelope = columns(&table);
    let runs: Vec<_> = SPEEDS.iter().map(|s| trajectory(&dir, s)).collect();
    let t = numbers(&envelope, "t");
    let t_run = numbers(&runs[0], "t [s]");
    assert_eq!(t.len(), t_run.len());
    assert!(t.iter().zip(&t_run).all(|(a, b)| (a - b).abs() < 1e-9));
    for (name, column) in [("r", "r [m]"), ("front_end.force", "front_end.force [N]")] {
        let histories: Vec<Vec<f64>> = runs.iter().map(|r| numbers(r, column)).collect();
        check_channel(&envelope, name, &histories);
    }
    let svg = std::fs::read_to_string(dir.join("envelope.svg")).unwrap();
    assert!(svg.contains("<polygon") && svg.contains("weighted mean"));
}

#[test]
fn threads_do_not_change_the_envelope_or_the_table() {
    let dir = temporary("envelope-threads");
    let mut files = Vec::new();
    for (threads, format) in [
        ("1", "csv"),
        ("2", "csv"),
        ("1", "parquet"),
        ("2", "parquet"),
    ] {
        let envelope = dir.join(format!("envelope-{threads}.{format}"));
        let o = sweep(
            &dir,
            &[
                "--threads",
                threads,
                "--envelope-out",
                envelope.to_str().unwrap(),
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
        files.push(std::fs::read(&envelope).unwrap());
    }
    assert!(files[0] == files[1], "CSV differs between 1 and 2 threads");
    assert!(
        files[2] == files[3],
        "Parquet differs between 1 and 2 threads"
    );
    // The table of a sweep with an envelope is that of one without.
    let with = std::fs::read(dir.join("sweep.csv")).unwrap();
    let plain = dir.join("plain.csv");
    let grid = format!("initial.velocities.r={}", SPEEDS.join(","));
    let o = lpm(&[
        "sweep",
        SCENARIO,
        "--quiet",
        "--set",
        T_END,
        "--grid",
        &grid,
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(with == std::fs::read(&plain).unwrap(), "the tables differ");
}

#[test]
fn bad_weights_and_partial_sweeps_are_refused_before_any_run() {
    let dir = temporary("envelope-refused");
    let table = dir.join("envelope.csv");
    let weights_file = dir.join("weights.csv");
    std::fs::write(&weights_file, "run,weight\n0,1\n1,1\n").unwrap();
    let out = table.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (
            &["--weights", "initial.velocities.r=0.2,-0.5,0.3"],
            "--weights initial.velocities.r=0.2,-0.5,0.3: the weight of initial.velocities.r = -15.5556 is -0.5; weights must be non-negative and finite",
        ),
        (
            &["--weights", "initial.velocities.r=0.5,0.5"],
            "2 weights for the 3 values of initial.velocities.r (-12, -15.5556, -18); give one per value",
        ),
        (
            &["--weights", "initial.velocities.r=0,0,0"],
            "every weight is 0",
        ),
        (
            &["--weights", weights_file.to_str().unwrap()],
            "no weight for run 2",
        ),
        (&["--envelope", "front_end.forse"], "front_end.force"),
    ];
    for (args, message) in cases {
        let o = sweep(&dir, &[&["--envelope-out", out][..], args].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!table.exists() && !dir.join("sweep.csv").exists());
    }
}

/// The weights of the tests on shards.
const WEIGHTED: [&str; 2] = ["--weights", "initial.velocities.r=0.2,0.5,0.3"];

/// Runs the sweep with `extra` into the table `out`.
fn succeeds(out: &Path, extra: &[&str]) -> std::process::Output {
    let o = sweep_to(out, extra);
    assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
    o
}

/// The partial envelope beside `part`.
fn envelope_beside(part: &Path) -> PathBuf {
    let mut name = part.file_name().unwrap().to_os_string();
    name.push(".envelope.json");
    part.with_file_name(name)
}

/// `--merge` of `parts` of `dir` into `out`, with the weights and the
/// envelope table `envelope`.
fn merge(dir: &Path, parts: &[&str], envelope: &str, out: &str) -> std::process::Output {
    let paths: Vec<String> = (parts.iter())
        .map(|p| dir.join(p).to_str().unwrap().to_string())
        .collect();
    let envelope = dir.join(envelope);
    let args = [
        &WEIGHTED[..],
        &["--envelope-out", envelope.to_str().unwrap(), "--merge"],
        &paths.iter().map(String::as_str).collect::<Vec<_>>(),
    ];
    sweep_to(&dir.join(out), &args.concat())
}

#[test]
fn shards_merged_in_any_order_and_resumed_sweeps_give_the_envelope_of_one_run() {
    let dir = temporary("envelope-shards");
    let path = |name: &str| dir.join(name);
    let envelope_out = |name: &str| {
        [
            "--envelope-out".to_string(),
            path(name).to_str().unwrap().to_string(),
        ]
    };
    let [flag, whole_envelope] = envelope_out("whole-envelope.csv");
    succeeds(
        &path("whole.csv"),
        &[&WEIGHTED[..], &[&flag, &whole_envelope]].concat(),
    );
    let whole = std::fs::read(path("whole-envelope.csv")).unwrap();
    // Three shards and two: each writes its table and its partial envelope
    // beside it, not the envelope table.
    let splits: [&[&str]; 2] = [&["a1.csv", "a2.parquet", "a3.csv"], &["b1.csv", "b2.csv"]];
    for parts in splits {
        for (k, part) in parts.iter().enumerate() {
            let shard = format!("{}/{}", k + 1, parts.len());
            let [flag, not_written] = envelope_out("shard-envelope.csv");
            let o = succeeds(
                &path(part),
                &[&WEIGHTED[..], &["--shard", &shard, &flag, &not_written]].concat(),
            );
            assert!(stdout(&o).contains("partial envelope of"), "{}", stdout(&o));
            assert!(envelope_beside(&path(part)).exists() && !Path::new(&not_written).exists());
        }
    }
    let merges: [(&[&str], &str); 3] = [
        (&["a3.csv", "a1.csv", "a2.parquet"], "merged-1.csv"),
        (&["a2.parquet", "a3.csv", "a1.csv"], "merged-2.csv"),
        (&["b2.csv", "b1.csv"], "merged-3.csv"),
    ];
    for (parts, envelope) in merges {
        let o = merge(&dir, parts, envelope, "m.csv");
        assert!(o.status.success(), "{parts:?}: {}", stderr(&o));
        assert!(stdout(&o).contains("envelope of 3 runs"), "{}", stdout(&o));
        let merged = std::fs::read(path(envelope)).unwrap();
        assert!(
            merged == whole,
            "{parts:?}: the envelope differs from one run's"
        );
    }
    // Its mean is the weighted mean of the runs' own trajectories.
    let runs: Vec<_> = SPEEDS.iter().map(|s| trajectory(&dir, s)).collect();
    let merged = columns(&path("merged-1.csv"));
    for (name, column) in [("r", "r [m]"), ("front_end.force", "front_end.force [N]")] {
        let histories: Vec<Vec<f64>> = runs.iter().map(|r| numbers(r, column)).collect();
        check_channel(&merged, name, &histories);
    }
    resumed_sweeps_give_the_same_envelope(&dir, &whole);
}

/// What a sweep killed after two runs leaves: its journal with two rows and
/// half of the third, and `saved` as the envelope saved beside it.
fn killed_after_two_runs(dir: &Path, out: &Path, saved: Option<&str>) {
    let table = std::fs::read_to_string(dir.join("whole.csv")).unwrap();
    let lines: Vec<&str> = table.split_inclusive('\n').collect();
    let journal = dir.join(format!(
        "{}.partial",
        out.file_name().unwrap().to_str().unwrap()
    ));
    std::fs::write(&journal, lines[..3].concat() + &lines[3][..10]).unwrap();
    if let Some(saved) = saved {
        std::fs::write(envelope_beside(&journal), saved).unwrap();
    }
}

/// A sweep killed after two runs resumes to the envelope `whole` of one
/// run: with no saved envelope (killed before the first save), and with one
/// saved after its first run (what the first shard of three holds).
fn resumed_sweeps_give_the_same_envelope(dir: &Path, whole: &[u8]) {
    let first_shard = std::fs::read_to_string(envelope_beside(&dir.join("a1.csv"))).unwrap();
    assert!(first_shard.contains(r#""block":[0,1],"done":1"#));
    let saved_after_one_run = first_shard.replace(r#""block":[0,1]"#, r#""block":[0,3]"#);
    for (name, saved) in [("r1", None), ("r2", Some(saved_after_one_run.as_str()))] {
        let out = dir.join(format!("{name}.csv"));
        killed_after_two_runs(dir, &out, saved);
        let envelope = dir.join(format!("{name}-envelope.csv"));
        let resume = ["--resume", "--envelope-out", envelope.to_str().unwrap()];
        let o = succeeds(&out, &[&WEIGHTED[..], &resume].concat());
        assert!(
            stdout(&o).contains("(2 from the journal, 1 now)"),
            "{}",
            stdout(&o)
        );
        assert!(
            std::fs::read(&envelope).unwrap() == whole,
            "{name}: the envelope differs"
        );
        let table = std::fs::read_to_string(dir.join("whole.csv")).unwrap();
        assert_eq!(std::fs::read_to_string(&out).unwrap(), table, "{name}");
        let journal = dir.join(format!("{name}.csv.partial"));
        assert!(!journal.exists() && !envelope_beside(&journal).exists());
    }
    // The saved envelope is what the resume starts from: one saved with
    // another total weight makes another mean.
    assert!(first_shard.contains(r#""total_weight":["0.2"]"#));
    let tampered =
        saved_after_one_run.replace(r#""total_weight":["0.2"]"#, r#""total_weight":["0.25"]"#);
    let out = dir.join("r3.csv");
    killed_after_two_runs(dir, &out, Some(&tampered));
    let envelope = dir.join("r3-envelope.csv");
    let resume = ["--resume", "--envelope-out", envelope.to_str().unwrap()];
    succeeds(&out, &[&WEIGHTED[..], &resume].concat());
    assert!(std::fs::read(&envelope).unwrap() != whole);
}

#[test]
fn partial_envelopes_of_another_sweep_or_missing_ones_are_refused_and_nothing_is_written() {
    let dir = temporary("envelope-refused-parts");
    let path = |name: &str| dir.join(name);
    let shard = |k: &str| {
        [
            "--shard".to_string(),
            format!("{k}/2"),
            "--envelope-out".into(),
            path("x.csv").to_str().unwrap().into(),
        ]
    };
    let [a, b, c, d] = shard("1");
    succeeds(
        &path("p1.csv"),
        &[&WEIGHTED[..], &[&a, &b, &c, &d]].concat(),
    );
    succeeds(&path("w1.csv"), &[&a, &b, &c, &d]);
    let [a, b, c, d] = shard("2");
    succeeds(
        &path("p2.csv"),
        &[&WEIGHTED[..], &[&a, &b, &c, &d]].concat(),
    );
    let o = sweep_of(
        "r",
        &path("c2.csv"),
        &[&WEIGHTED[..], &[&a, &b, &c, &d]].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let grid = format!("initial.velocities.r={}", SPEEDS.join(","));
    let plain = [
        "sweep", SCENARIO, "--quiet", "--set", T_END, "--grid", &grid, "--shard", "2/2",
    ];
    let n2 = path("n2.csv");
    assert!(
        lpm(&[&plain[..], &["--out", n2.to_str().unwrap()]].concat())
            .status
            .success()
    );
    let beside = |part: &str| envelope_beside(&path(part)).display().to_string();
    let cases = [
        (
            "w1.csv",
            "p2.csv",
            format!(
                "{}: not a part of this sweep: its runs have other --weights than this sweep's",
                beside("w1.csv")
            ),
        ),
        (
            "p1.csv",
            "c2.csv",
            format!(
                "{}: not a part of this sweep: its channels are r, this sweep's r,front_end.force",
                beside("c2.csv")
            ),
        ),
        (
            "p1.csv",
            "n2.csv",
            format!(
                "{} is missing: the shard that wrote {} ran without --envelope",
                beside("n2.csv"),
                n2.display()
            ),
        ),
    ];
    for (first, second, message) in cases {
        let o = merge(&dir, &[first, second], "e.csv", "m.csv");
        assert_eq!(o.status.code(), Some(7), "{second}: {}", stderr(&o));
        assert!(stderr(&o).contains(&message), "{second}: {}", stderr(&o));
        assert!(!path("e.csv").exists() && !path("m.csv").exists());
    }
    // A resume against an envelope saved with other weights.
    succeeds(&path("whole.csv"), &[&c, &d]);
    let saved = std::fs::read_to_string(envelope_beside(&path("w1.csv"))).unwrap();
    let saved = saved.replace(r#""block":[0,1]"#, r#""block":[0,3]"#);
    killed_after_two_runs(&dir, &path("r.csv"), Some(&saved));
    let e = path("e.csv");
    let resume = ["--resume", "--envelope-out", e.to_str().unwrap()];
    let o = sweep_to(&path("r.csv"), &[&WEIGHTED[..], &resume].concat());
    assert_eq!(o.status.code(), Some(7), "{}", stderr(&o));
    let message = format!(
        "--resume: {}: not a part of this sweep: its runs have other --weights",
        beside("r.csv.partial")
    );
    assert!(stderr(&o).contains(&message), "{}", stderr(&o));
    assert!(!path("e.csv").exists() && !path("r.csv").exists());
}
