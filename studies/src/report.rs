//! The report of one run, `report.html`: one self-contained page an
//! engineer hands on — the summary, the warnings, the plots, the events,
//! the audit of the spec's hand-derived equations and the derived
//! equations of motion. No script, no style sheet, font or image from
//! elsewhere: the plots are inline SVG and the page works offline.

use crate::compare::Comparison;
use lagrangian_core::Compiled;
use lagrangian_core::audit::{AuditReport, Part, Verdict, audit};
use lagrangian_core::emit::{Notation, render_equations};
use lagrangian_sim::criteria::Criteria;
use lagrangian_sim::criteria::limits::{self, Limit, Protocol, limits};
use lagrangian_sim::simulate::SimulationResult;
use std::fmt::Write;

/// The page's style: print-friendly, one column.
const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:60rem;margin:1.5rem auto;\
padding:0 1rem;color:#111}h1{font-size:1.4rem;margin-bottom:.2rem}h2{font-size:1.1rem;\
border-bottom:1px solid #bbb;margin-top:1.6rem}table{border-collapse:collapse}\
td,th{padding:.15rem .8rem .15rem 0;text-align:left;vertical-align:top}\
td.value{font-variant-numeric:tabular-nums;white-space:nowrap}.key{color:#666;font-size:.8rem}\
.meta{color:#444}.warning{color:#8a4b00}.disagrees{color:#a00;font-weight:600}\
pre{white-space:pre-wrap;font-size:.8rem;background:#f6f6f6;padding:.6rem}\
svg{max-width:100%;height:auto}@media print{h2{break-after:avoid}}";

/// What the report shows of the spec: its equations of motion and the
/// audit of its hand-derived ones.
pub struct Derived {
    /// The equations, as `lpm derive` prints them.
    pub equations: String,
    /// The audit, for a spec with hand-derived equations.
    pub audit: Option<AuditReport>,
}

impl Derived {
    /// The equations and audit of `compiled` (which caches what they
    /// derive, hence `&mut`).
    pub fn of(compiled: &mut Compiled) -> Derived {
        Derived {
            equations: render_equations(compiled, Notation::Text),
            audit: audit(compiled),
        }
    }
}

/// What the report shows besides the run: the spec's equations and audit
/// and the plots of the run (`plots.svg`).
pub struct ReportParts<'a> {
    /// The run.
    pub result: &'a SimulationResult,
    /// The scenario's file, or that there was none.
    pub scenario_name: &'a str,
    /// The spec's equations and audit.
    pub derived: &'a Derived,
    /// The spec's file, as the page names it.
    pub spec: &'a str,
    /// The plots, an SVG document.
    pub plots_svg: &'a str,
    /// The run rated against a test, with the overlays of each pair.
    pub test: Option<&'a Comparison>,
}

/// The page.
pub fn report_html(parts: &ReportParts) -> String {
    let result = parts.result;
    let title = format!("{} — {}", result.model, parts.scenario_name);
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n",
        escape(&title)
    );
    let _ = writeln!(page, "<h1>{}</h1>", escape(&title));
    let _ = writeln!(
        page,
        "<p class=\"meta\">spec {} · {}: {} steps, {} rejected · lpm {}</p>",
        escape(parts.spec),
        escape(&result.method.to_string()),
        result.summary.steps,
        result.summary.rejected_steps,
        env!("CARGO_PKG_VERSION")
    );
    page.push_str(&summary(result));
    page.push_str(&channels(result));
    page.push_str(&criteria_section(&result.summary.criteria));
    page.push_str(&warnings(result));
    let _ = writeln!(
        page,
        "<h2 id=\"plots\">Plots</h2>\n{}",
        inline_svg(parts.plots_svg)
    );
    page.push_str(&test_section(parts.test));
    page.push_str(&events(result));
    page.push_str(&audit_section(parts.derived.audit.as_ref()));
    page.push_str(&equations(&parts.derived.equations));
    page.push_str("</body>\n</html>\n");
    page
}

/// The summary's rows, each metric with its `summary.json` key.
fn summary(result: &SimulationResult) -> String {
    let mut out = String::from("<h2 id=\"summary\">Summary</h2>\n<table>\n");
    for row in result.summary.rows() {
        let values: Vec<String> = (row.values.iter())
            .map(|(key, shown)| {
                format!(
                    "{} <span class=\"key\">{}</span>",
                    escape(shown),
                    escape(key)
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "<tr><th>{}</th><td class=\"value\">{}</td><td>{}</td></tr>",
            escape(row.label),
            values.join(", "),
            escape(row.note.trim())
        );
    }
    for (name, energy) in &result.summary.dissipated_by {
        let _ = writeln!(
            out,
            "<tr><th>dissipated by {}</th><td class=\"value\">{energy:.4e} J</td><td></td></tr>",
            escape(name)
        );
    }
    out.push_str("</table>\n");
    out
}

/// The injury criteria of the run's occupant channels, each against the
/// limits of FMVSS 208 and Euro NCAP for the dummy; nothing where there
/// are none.
fn criteria_section(criteria: &Criteria) -> String {
    if criteria.is_empty() {
        return String::new();
    }
    let dummy = criteria
        .dummy
        .map_or("no dummy named".to_string(), |d| d.to_string());
    let mut out = format!(
        "<h2 id=\"criteria\">Injury criteria</h2>\n<p class=\"meta\">dummy: {}</p>\n<table>\n\
         <tr><th>criterion</th><th>value</th>",
        escape(&dummy)
    );
    for protocol in Protocol::ALL {
        let _ = write!(out, "<th>{}</th>", escape(protocol.name()));
    }
    out.push_str("<th>channels</th></tr>\n");
    for rated in &criteria.rated {
        let c = rated.criterion;
        let _ = write!(
            out,
            "<tr><th>{} <span class=\"key\">{}</span></th><td class=\"value\">{}</td>",
            escape(c.label()),
            escape(c.key()),
            escape(&with_unit(rated.value, c.unit()))
        );
        for protocol in Protocol::ALL {
            let limit = criteria.dummy.and_then(|dummy| {
                limits(protocol, dummy)
                    .into_iter()
                    .find(|l| l.criterion == c)
            });
            let _ = write!(
                out,
                "<td>{}</td>",
                limit.map_or("–".into(), |l| judged(&l, rated.value))
            );
        }
        let _ = writeln!(out, "<td>{}</td></tr>", escape(&rated.from.join(", ")));
    }
    out.push_str("</table>\n");
    out
}

/// A criterion's value to four significant digits, with its unit.
fn with_unit(value: f64, unit: &str) -> String {
    let digits = (3 - value.abs().log10().floor().clamp(-3.0, 3.0) as i32).max(0) as usize;
    match unit {
        "" => format!("{value:.digits$}"),
        unit => format!("{value:.digits$} {unit}"),
    }
}

/// The verdict on `value` against `limit`, with the limit: `"pass (≤ 700)"`,
/// `"2.4 of 4 points (500–700)"`.
fn judged(limit: &Limit, value: f64) -> String {
    let unit = match limit.criterion.unit() {
        "" => String::new(),
        unit => format!(" {unit}"),
    };
    let lower = limit.lower;
    match (limit.judge(value), limit.higher) {
        (limits::Verdict::Pass, _) => format!("pass (≤ {lower}{unit})"),
        (limits::Verdict::Fail, _) => {
            format!("<span class=\"disagrees\">fail</span> (≤ {lower}{unit})")
        }
        (limits::Verdict::Points(points), higher) => format!(
            "{points:.2} of 4 points ({}–{lower}{unit})",
            higher.unwrap_or(lower)
        ),
    }
}

/// The run against the test: each pair's ISO/TS 18571 scores and grade,
/// then its overlay (the test and the run over the interval rated);
/// nothing without a test.
fn test_section(comparison: Option<&Comparison>) -> String {
    let Some(comparison) = comparison else {
        return String::new();
    };
    let mut out = format!(
        "<h2 id=\"test\">Against the test</h2>\n<p class=\"meta\">{} · ISO/TS 18571</p>\n<table>\n\
         <tr><th>test channel</th><th>run</th><th>corridor</th><th>phase</th><th>magnitude</th>\
         <th>slope</th><th>overall</th><th>grade</th></tr>\n",
        escape(&comparison.reference.display().to_string())
    );
    for pair in &comparison.pairs {
        let r = &pair.rating;
        let _ = writeln!(
            out,
            "<tr><th>{}</th><td>{}</td><td class=\"value\">{:.3}</td><td class=\"value\">{:.3}</td>\
             <td class=\"value\">{:.3}</td><td class=\"value\">{:.3}</td><td class=\"value\">{:.3}</td>\
             <td>{}</td></tr>",
            escape(&pair.reference.name),
            escape(&pair.comparison.name),
            r.corridor,
            r.phase,
            r.magnitude,
            r.slope,
            r.overall,
            r.grade.name()
        );
    }
    out.push_str("</table>\n");
    for skipped in &comparison.skipped {
        let _ = writeln!(
            out,
            "<p class=\"warning\">{}</p>",
            escape(&skipped.reason())
        );
    }
    match crate::compare::plots(comparison) {
        Ok(plots) => {
            for (_, svg) in plots {
                out.push_str(inline_svg(&svg));
                out.push('\n');
            }
        }
        Err(e) => {
            let _ = writeln!(out, "<p class=\"warning\">{}</p>", escape(&e.to_string()));
        }
    }
    out
}

/// The scenario's channels (their extremes, an acceleration's peaks) and
/// the constraints' lines, as the text summary has them; nothing where
/// there are none.
fn channels(result: &SimulationResult) -> String {
    let mut out = String::new();
    if !result.summary.channels.0.is_empty() {
        out.push_str("<h2 id=\"channels\">Channels</h2>\n<ul>\n");
        for channel in &result.summary.channels.0 {
            let _ = writeln!(out, "<li>{}</li>", escape(&channel.text_line()));
        }
        out.push_str("</ul>\n");
    }
    let constraints = lagrangian_sim::report::constraint_lines(result);
    if !constraints.is_empty() {
        let _ = writeln!(
            out,
            "<h2 id=\"constraints\">Constraints</h2>\n<pre>{}</pre>",
            escape(&constraints)
        );
    }
    out
}

/// The run's warnings, or that there are none.
fn warnings(result: &SimulationResult) -> String {
    let warnings = &result.warnings;
    let mut out = String::from("<h2 id=\"warnings\">Warnings</h2>\n");
    if warnings.is_empty() {
        out.push_str("<p>None.</p>\n");
        return out;
    }
    out.push_str("<ul>\n");
    for w in warnings {
        let _ = writeln!(
            out,
            "<li class=\"warning\"><b>{}</b>: {}</li>",
            escape(w.kind()),
            escape(&w.message())
        );
    }
    out.push_str("</ul>\n");
    out
}

/// The events of the run, in time order.
fn events(result: &SimulationResult) -> String {
    let events = &result.events;
    let mut out = String::from("<h2 id=\"events\">Events</h2>\n");
    if events.is_empty() {
        out.push_str("<p>None.</p>\n");
        return out;
    }
    out.push_str("<table>\n<tr><th>t [ms]</th><th>component</th><th>what</th></tr>\n");
    for e in events {
        let _ = writeln!(
            out,
            "<tr><td class=\"value\">{:.2}</td><td>{}</td><td>{}</td></tr>",
            e.t * 1e3,
            escape(&e.component),
            escape(&e.description)
        );
    }
    out.push_str("</table>\n");
    out
}

/// The verdict of each part of the audit of the spec's hand-derived
/// equations (`lpm audit`), or that the spec has none.
fn audit_section(report: Option<&AuditReport>) -> String {
    let mut out = String::from("<h2 id=\"audit\">Audit of the hand-derived equations</h2>\n");
    let Some(report) = report else {
        out.push_str("<p>The spec has no hand-derived equations to audit.</p>\n");
        return out;
    };
    out.push_str("<table>\n<tr><th>part</th><th>verdict</th><th>max residual</th></tr>\n");
    for a in &report.audits {
        let part = match a.part {
            Part::Equation => format!("equation of {}", a.coordinate),
            Part::GeneralizedForce => format!("generalized force Q of {}", a.coordinate),
        };
        let (verdict, class) = match a.verdict {
            Verdict::Exact => ("exact", ""),
            Verdict::Numerical => ("agrees numerically", ""),
            Verdict::SmallAngle => ("agrees to small angles", ""),
            Verdict::Disagrees => ("disagrees", " class=\"disagrees\""),
        };
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td{class}>{verdict}</td><td class=\"value\">{:.1e}</td></tr>",
            escape(&part),
            a.max_residual
        );
    }
    out.push_str("</table>\n<p class=\"meta\">Details: <code>lpm audit SPEC</code>.</p>\n");
    out
}

/// The derived equations of motion, as `lpm derive` prints them.
fn equations(text: &str) -> String {
    format!(
        "<h2 id=\"equations\">Equations of motion</h2>\n<pre>{}</pre>\n",
        escape(text)
    )
}

/// An SVG document as an element of the page: without its XML declaration.
fn inline_svg(svg: &str) -> &str {
    let svg = svg.trim_start();
    match svg.strip_prefix("<?xml") {
        Some(rest) => rest
            .split_once("?>")
            .map_or(svg, |(_, body)| body.trim_start()),
        None => svg,
    }
}

/// `text` with the characters HTML gives a meaning escaped.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped_and_an_svg_loses_its_declaration() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
        let svg = "<?xml version=\"1.0\"?>\n<svg viewBox=\"0 0 1 1\"></svg>";
        assert_eq!(inline_svg(svg), "<svg viewBox=\"0 0 1 1\"></svg>");
        assert_eq!(inline_svg("<svg/>"), "<svg/>");
    }

    #[test]
    fn criteria_are_judged_against_each_protocol_for_the_dummy() {
        use lagrangian_sim::criteria::{Criterion, Dummy, Rated};
        let rated = |criterion, value| Rated {
            criterion,
            value,
            from: vec!["head".into()],
            when: None,
        };
        let criteria = Criteria {
            dummy: Some(Dummy::Hybrid3Female5),
            rated: vec![
                rated(Criterion::Hic15, 600.0),
                rated(Criterion::ChestDeflection, 55.0),
            ],
            warnings: Vec::new(),
        };
        let html = criteria_section(&criteria);
        assert!(
            html.contains("<td>pass (≤ 700)</td><td>2.00 of 4 points (500–700)</td>"),
            "{html}"
        );
        assert!(
            html.contains("fail</span> (≤ 52 mm)</td><td>0.00 of 4 points (18–34 mm)</td>"),
            "{html}"
        );
        assert_eq!(criteria_section(&Criteria::EMPTY), "");
    }
}
