//! `lpm simulate --report`: report.html beside the other outputs, one page
//! that needs nothing from elsewhere and shows what the command printed.

mod common;

use common::{lpm, stderr, stdout, temporary};
use std::path::Path;

/// Runs `lpm simulate SPEC --report` into a fresh folder: the command's
/// text and the page.
fn report(spec: &str, name: &str) -> (String, String) {
    let out = temporary(name);
    let run = lpm(&["simulate", spec, "--report", "--out", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    (stdout(&run), page)
}

/// The page asks for nothing from elsewhere: no script, style sheet, image
/// or font by address (the SVG namespace is a name, not a fetch).
fn assert_self_contained(page: &str) {
    for fetching in [
        "<script", "<link", "src=", "href=", "url(", "@import", "<iframe",
    ] {
        assert!(!page.contains(fetching), "the page has {fetching}");
    }
    let addresses = page.matches("http").count();
    let namespaces = page.matches("xmlns=\"http://www.w3.org/2000/svg\"").count();
    assert_eq!(
        addresses, namespaces,
        "an address besides the SVG namespace"
    );
    for tag in ["html", "head", "body", "table", "tr", "svg", "pre", "h2"] {
        let opened =
            page.matches(&format!("<{tag}>")).count() + page.matches(&format!("<{tag} ")).count();
        let closed = page.matches(&format!("</{tag}>")).count();
        assert_eq!(opened, closed, "<{tag}> opened {opened}, closed {closed}");
    }
}

#[test]
fn the_paper_report_shows_the_summary_events_and_the_failed_audit() {
    let (text, page) = report("specs/yaris_double_pendulum.lpm", "report-yaris");
    assert_self_contained(&page);
    assert!(page.starts_with("<!DOCTYPE html>"));
    // Each value the command prints is on the page (the text summary's
    // lines: a label, then values separated by commas).
    let metrics = text.lines().skip(1);
    for line in metrics.take_while(|l| !l.starts_with("  channels:") && !l.starts_with("  solver"))
    {
        let Some(values) = line.get(25..) else {
            continue;
        };
        for value in values.split(", ") {
            let value = value.split(" (").next().unwrap().trim();
            if !value.is_empty() && !line.contains("dissipated by") {
                assert!(
                    page.contains(value),
                    "{value} of `{line}` is not on the page"
                );
            }
        }
    }
    // Every channel's line.
    let channels = text
        .lines()
        .skip_while(|l| !l.starts_with("  channels:"))
        .skip(1);
    for channel in channels.take_while(|l| l.starts_with("    ")) {
        assert!(
            page.contains(&format!("<li>{}</li>", channel.trim())),
            "{channel}"
        );
    }
    // Every event, at its time.
    let events = text
        .lines()
        .skip_while(|l| !l.starts_with("  events:"))
        .skip(1);
    for event in events.take_while(|l| l.starts_with("    ")) {
        let (time, what) = event.trim().split_once(" ms  ").unwrap();
        let (component, description) = what.split_once(": ").unwrap();
        let row =
            format!("<td class=\"value\">{time}</td><td>{component}</td><td>{description}</td>");
        assert!(page.contains(&row), "{row}");
    }
    // The paper's hand-derived equations are wrong (`lpm audit` exits 5).
    assert!(page.contains("<td class=\"disagrees\">disagrees</td>"));
    assert!(page.contains("<h2 id=\"equations\">Equations of motion</h2>\n<pre>"));
    assert!(page.contains("<svg"));
}

#[test]
fn a_report_is_written_on_request_only_and_for_every_shipped_scenario() {
    let out = temporary("report-none");
    let run = lpm(&[
        "simulate",
        "specs/wall_impact.lpm",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(!out.join("report.html").exists());
    assert!(!stdout(&run).contains("report.html"));
    let _ = std::fs::remove_dir_all(&out);
    let scenarios =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("../specs/scenarios"));
    let mut specs: Vec<String> = (scenarios.unwrap())
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            let table: toml::Table = text.parse().unwrap();
            let spec = table["spec"].as_str().unwrap().trim_start_matches("../");
            format!("specs/{spec}")
        })
        .collect();
    specs.sort();
    specs.dedup();
    assert!(specs.len() >= 6, "{specs:?}");
    for spec in &specs {
        let (_, page) = report(spec, "report-each");
        assert_self_contained(&page);
        // No tick reads "-0.0" (a tick a rounding error below zero).
        let negative_zero = |l: &str| {
            let l = l.trim();
            l.len() > 1 && l.starts_with('-') && l[1..].chars().all(|c| c == '0' || c == '.')
        };
        assert!(!page.lines().any(negative_zero), "{spec}: a -0 tick");
        let audited = page.contains("<th>verdict</th>");
        let none = page.contains("The spec has no hand-derived equations to audit.");
        assert!(audited != none, "{spec}: the audit section");
    }
}

/// With a test, the report rates the run against it and overlays the pair;
/// its scores are `lpm compare`'s of the same pair (one answer).
#[test]
fn a_report_with_a_test_has_the_ratings_of_lpm_compare_and_the_overlay() {
    let out = temporary("report-test");
    let (test, pair) = ("specs/data/yaris_pulse.csv", "deceleration=r_ddot");
    let run = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--report",
        "--test",
        test,
        "--test-channel",
        pair,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert_self_contained(&page);
    let compared = lpm(&[
        "compare",
        test,
        out.to_str().unwrap(),
        "--channel",
        pair,
        "--format",
        "json",
    ]);
    assert!(compared.status.success(), "{}", stderr(&compared));
    let rating: serde_json::Value = serde_json::from_str(&stdout(&compared)).unwrap();
    let rated = &rating["pairs"][0];
    let row = format!(
        "<tr><th>deceleration</th><td>r_ddot</td><td class=\"value\">{:.3}</td><td class=\"value\">{:.3}</td>",
        rated["corridor"].as_f64().unwrap(),
        rated["phase"].as_f64().unwrap()
    );
    assert!(page.contains("<h2 id=\"test\">Against the test</h2>"));
    assert!(page.contains(&row), "no row {row}");
    assert!(page.contains(&format!(
        "<td>{}</td></tr>",
        rated["grade"].as_str().unwrap()
    )));
    // The overlay: one more SVG than the plots.
    assert_eq!(page.matches("<svg").count(), 2);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_test_needs_the_report() {
    let run = lpm(&[
        "simulate",
        "specs/yaris_double_pendulum.lpm",
        "--test",
        "specs/data/yaris_pulse.csv",
    ]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("--report"), "{}", stderr(&run));
}
