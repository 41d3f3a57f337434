//! `lpm audit`: compare a spec's hand-derived equations with the derivation.

use crate::failure::{Failure, Outcome};
use crate::status::ExitStatus;
use lagrangian_core::audit::{AuditReport, Finding, GroupVerdict, Part, Verdict, audit, markdown};
use lagrangian_studies::files::Files;
use lagrangian_studies::spec::compile;
use serde_json::{Value, json};
use std::path::PathBuf;
use std::sync::Arc;

/// Options of `lpm audit`.
#[derive(clap::Args)]
pub struct Args {
    /// The spec file (`.lpm`) with a `hand_derived` section.
    spec: PathBuf,
    #[arg(long, value_parser = ["markdown", "json"], default_value = "markdown")]
    format: String,
}

/// Runs `lpm audit`: the report, with status 5 when anything disagrees.
pub fn run(args: Args, files: &Arc<dyn Files>) -> Result<Outcome, Failure> {
    let spec = &args.spec;
    let mut compiled = compile(&**files, spec)?;
    let report = audit(&mut compiled).ok_or_else(|| {
        Failure::usage(format!(
            "{} has no `hand_derived` section to audit",
            spec.display()
        ))
    })?;
    let text = if args.format == "json" {
        format!(
            "{}\n",
            serde_json::to_string_pretty(&to_json(&report)).unwrap_or_default()
        )
    } else {
        markdown(&report, &spec.display().to_string())
    };
    let status = if report.disagrees() {
        ExitStatus::AuditDisagrees
    } else {
        ExitStatus::Success
    };
    Ok(Outcome { text, status })
}

fn to_json(report: &AuditReport) -> Value {
    let audits: Vec<Value> = report
        .audits
        .iter()
        .map(|a| {
            json!({
                "part": match a.part { Part::Equation => "equation", Part::GeneralizedForce => "generalized_force" },
                "coordinate": a.coordinate,
                "verdict": match a.verdict { Verdict::Exact => "exact", Verdict::Numerical => "numerical", Verdict::SmallAngle => "small_angle", Verdict::Disagrees => "disagrees" },
                "max_residual": a.max_residual,
                "median_residual": a.median_residual,
                "dimension_findings": a.dimension_findings.iter().map(|f| json!({
                    "term": f.term, "line": f.line, "found": f.found.to_string(), "expected": f.expected.to_string(),
                })).collect::<Vec<_>>(),
                "groups": a.groups.iter().map(|g| json!({
                    "multiplies": g.motion,
                    "derived": g.derived,
                    "hand": g.hand,
                    "comparison": match g.verdict {
                        GroupVerdict::Match => "match",
                        GroupVerdict::NumericalMatch => "numerical_match",
                        GroupVerdict::SmallAngle => "small_angle",
                        GroupVerdict::Differs => "differs",
                        GroupVerdict::MissingByHand => "missing_by_hand",
                        GroupVerdict::ExtraByHand => "extra_by_hand",
                    },
                    "findings": g.findings.iter().map(|f| match f {
                        Finding::Missing { term, .. } => json!({"kind": "missing_by_hand", "terms": term}),
                        Finding::Extra { term, .. } => json!({"kind": "extra_by_hand", "terms": term}),
                        Finding::Sign { term, .. } => json!({"kind": "opposite_sign", "terms": term}),
                        Finding::Scaled { term, ratio, .. } => json!({"kind": "scaled", "terms": term, "hand_over_derived": ratio.to_string()}),
                    }).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "model": report.model,
        "convention": report.convention,
        "small_angle_order": report.small_angle_order,
        "assumptions": report.assumptions.iter().map(|(n, v)| json!({"name": n, "value": v})).collect::<Vec<_>>(),
        "states": report.states,
        "disagrees": report.disagrees(),
        "audits": audits,
    })
}
