//! `lpm sweep --envelope`: envelopes and weighted mean histories, checked
//! against the runs' own trajectories from `lpm simulate`; independent of
//! the number of threads; bad weights and partial sweeps refused.

mod common;

use common::{lpm, stderr, temporary};
use std::path::Path;

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
    let out = dir.join("sweep.csv");
    let grid = format!("initial.velocities.r={}", SPEEDS.join(","));
    let args = [
        &[
            "sweep", SCENARIO, "--quiet", "--set", T_END, "--grid", &grid,
        ][..],
        &[
            "--envelope",
            "r,front_end.force",
            "--out",
            out.to_str().unwrap(),
        ],
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
    let cases: [(&[&str], &str); 7] = [
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
        (&["--shard", "1/2"], "--envelope with a shard"),
        (&["--resume"], "--envelope with --resume"),
        (&["--envelope", "front_end.forse"], "front_end.force"),
    ];
    for (args, message) in cases {
        let o = sweep(&dir, &[&["--envelope-out", out][..], args].concat());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{args:?}: {}", stderr(&o));
        assert!(!table.exists() && !dir.join("sweep.csv").exists());
    }
}
