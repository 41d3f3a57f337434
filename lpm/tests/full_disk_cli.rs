//! Outputs on a full disk: a 64 KiB tmpfs (mounted for the test; skipped,
//! saying why, where mounting is not permitted) filled to the last byte,
//! or to its last page. Every command fails with an I/O error and leaves
//! no file behind — no hidden temporary, no 0-byte output or journal —
//! and a sweep that ran out of room mid-way keeps its finished runs for
//! `--resume`.

mod common;

use common::{lpm, stderr, temporary};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A mounted tmpfs of `size`, unmounted when dropped.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(name: &str) -> Option<Tmpfs> {
        let dir = temporary(name);
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", "size=64k", "tmpfs"])
            .arg(&dir)
            .output();
        match mounted {
            Ok(o) if o.status.success() => Some(Tmpfs(dir)),
            Ok(o) => {
                println!(
                    "skipped: cannot mount a tmpfs ({})",
                    String::from_utf8_lossy(&o.stderr).trim()
                );
                None
            }
            Err(e) => {
                println!("skipped: cannot run mount ({e})");
                None
            }
        }
    }

    /// Fills the file system but for `free` bytes (a multiple of 4 KiB).
    fn fill(&self, free: usize) {
        std::fs::write(self.0.join("filler"), vec![0u8; 65536 - free]).unwrap();
    }

    /// Every file under the mount but the filler, hidden ones included.
    fn files(&self) -> Vec<String> {
        fn walk(dir: &Path, out: &mut Vec<String>) {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    walk(&path, out);
                } else if path.file_name().unwrap() != "filler" {
                    out.push(path.display().to_string());
                }
            }
        }
        let mut out = Vec::new();
        walk(&self.0, &mut out);
        out
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `lpm ARGS` fails with status 1 ("cannot write … No space left") and
/// leaves no file on the tmpfs.
fn fails_and_leaves_nothing(disk: &Tmpfs, args: &[&str]) {
    let run = lpm(args);
    assert_eq!(run.status.code(), Some(1), "{args:?}: {}", stderr(&run));
    assert!(
        stderr(&run).contains("No space left on device"),
        "{args:?}: {}",
        stderr(&run)
    );
    assert_eq!(disk.files(), Vec::<String>::new(), "{args:?} left files");
}

#[test]
fn on_a_full_disk_every_command_fails_and_leaves_no_file() {
    let Some(disk) = Tmpfs::mount("full-disk") else {
        return;
    };
    let at = |name: &str| disk.0.join(name).display().to_string();
    // To the last byte, then with one page free: the first write fails,
    // or one fails part-way.
    for free in [0, 4096] {
        disk.fill(free);
        let (sim, fit, lin) = (at("sim"), at("fit"), at("lin.md"));
        fails_and_leaves_nothing(
            &disk,
            &["simulate", "specs/yaris_double_pendulum.lpm", "--out", &sim],
        );
        fails_and_leaves_nothing(
            &disk,
            &[
                "fit",
                "specs/yaris_double_pendulum.lpm",
                "--target",
                "specs/data/yaris_pulse.csv",
                "--fit",
                "stiffness",
                "--starts",
                "1",
                "--quiet",
                "--out",
                &fit,
            ],
        );
        // Its report (20 states, 4.2 kB) is larger than a page.
        fails_and_leaves_nothing(
            &disk,
            &["linearize", "specs/pendulum_chain_10.lpm", "--out", &lin],
        );
    }
    disk.fill(0);
    for out in [at("sweep.csv"), at("sweep.parquet")] {
        fails_and_leaves_nothing(
            &disk,
            &[
                "sweep",
                "specs/scenarios/yaris_full_frontal.toml",
                "--grid",
                "k1*=0.9,1.1",
                "--set",
                "simulation.t_end=0.005",
                "--quiet",
                "--out",
                &out,
            ],
        );
    }
}

/// A sweep that runs out of room keeps the runs it finished in its
/// journal; with room made, `--resume` finishes it, and the table is that
/// of a sweep that never stopped.
#[test]
fn a_sweep_out_of_room_resumes_once_there_is_room() {
    let Some(disk) = Tmpfs::mount("full-sweep") else {
        return;
    };
    disk.fill(4096);
    let out = disk.0.join("sweep.csv").display().to_string();
    let args = [
        "sweep",
        "specs/scenarios/yaris_full_frontal.toml",
        "--grid",
        "k1*=0.8:1.2:120",
        "--set",
        "simulation.t_end=0.005",
        "--threads",
        "1",
        "--quiet",
        "--out",
        &out,
    ];
    let run = lpm(&args);
    assert_eq!(run.status.code(), Some(1), "{}", stderr(&run));
    assert!(stderr(&run).contains("--resume"), "{}", stderr(&run));
    assert_eq!(disk.files(), [format!("{out}.partial")]);
    std::fs::remove_file(disk.0.join("filler")).unwrap();
    let mut resume = args.to_vec();
    resume.push("--resume");
    let run = lpm(&resume);
    assert!(run.status.success(), "{}", stderr(&run));
    let resumed = std::fs::read_to_string(&out).unwrap();
    let whole = temporary("full-sweep-whole").join("sweep.csv");
    let mut fresh = args.to_vec();
    let whole_text = whole.display().to_string();
    *fresh.last_mut().unwrap() = &whole_text;
    let run = lpm(&fresh);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(resumed, std::fs::read_to_string(&whole).unwrap());
    assert_eq!(resumed.lines().count(), 121);
}
