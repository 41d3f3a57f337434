//! `lpm metrics`: the pulse metrics and injury criteria of a measured test —
//! an ISO-MME test (its vehicle's pulse and every occupant's criteria) or
//! a CSV of the vehicle's pulse ([`lagrangian_sim::pulse::channels`]).

use crate::error::StudyError;
use crate::test_data::{self, Occupant, is_iso_mme, read_iso_mme, si_values, vehicle_acceleration};
use lagrangian_crashdata::code::{Dimension, Direction};
use lagrangian_crashdata::isomme::Test;
use lagrangian_sim::criteria::roadside::head_impact;
use lagrangian_sim::criteria::{Criteria, Criterion, Dummy, Rated, rate};
use lagrangian_sim::files::Files;
use lagrangian_sim::pulse::channels::{Quantity, read_time_histories};
use lagrangian_sim::pulse::{Pulse, PulseMetrics, cfc_filter, integrate};
use lagrangian_sim::warning::{self, Warning};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What `lpm metrics` is asked.
pub struct MetricsRequest {
    /// The test: an ISO-MME test (folder, `.mme`, `.zip`) or a CSV.
    pub test: PathBuf,
    /// The impact velocity [m/s], where the test does not give it.
    pub v0: Option<f64>,
}

/// The criteria of one occupant of a test.
#[derive(Clone, Debug, Serialize)]
pub struct OccupantCriteria {
    /// Its test object (`"1"`).
    pub test_object: String,
    /// Its seat (`"1"` the driver).
    pub position: String,
    /// Its dummy, where its codes name one the criteria know.
    pub dummy: Option<String>,
    /// Its criteria.
    pub criteria: Criteria,
}

/// The metrics of a test.
#[derive(Clone, Debug, Serialize)]
pub struct TestMetrics {
    /// The vehicle's pulse metrics, where the test has the vehicle's
    /// longitudinal acceleration.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub pulse: Option<PulseMetrics>,
    /// The vehicle's criteria and the first occupant's (the driver, in a
    /// test with several).
    pub criteria: Criteria,
    /// Every occupant's criteria, by test object and seat (none for a CSV).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub occupants: Vec<OccupantCriteria>,
    /// The channel the vehicle's pulse was read from.
    #[serde(skip)]
    pub pulse_channel: Option<String>,
    /// What looked wrong.
    #[serde(skip)]
    pub warnings: Vec<Warning>,
}

impl TestMetrics {
    /// `summary.json`-like JSON: the metrics, then their `warnings`.
    pub fn json(&self) -> String {
        warning::json_with_warnings(self, &self.warnings)
    }
}

/// The metrics of the test `request` names. Every CSV is read from `files`;
/// an ISO-MME test from its folder or archive.
pub fn test_metrics(
    files: &dyn Files,
    request: &MetricsRequest,
) -> Result<TestMetrics, StudyError> {
    match is_iso_mme(&request.test) {
        true => iso_mme_metrics(&read_iso_mme(&request.test)?, request),
        false => csv_metrics(files, request),
    }
}

fn csv_metrics(files: &dyn Files, request: &MetricsRequest) -> Result<TestMetrics, StudyError> {
    let file = request.test.as_path();
    let histories = read_time_histories(files, file).map_err(|e| StudyError::channels(&e))?;
    let Some(acceleration) = histories.channel(Quantity::Acceleration) else {
        return Err(StudyError::usage(format!(
            "{}: the metrics need an acceleration (or deceleration) column",
            file.display()
        )));
    };
    let v0 = match (request.v0, histories.channel(Quantity::Velocity)) {
        (Some(v), _) => v,
        (None, Some(v)) => v.values[0],
        (None, None) => {
            return Err(StudyError::usage(format!(
                "{}: no velocity column to take the impact velocity from; give it with --v0 <m/s>",
                file.display()
            )));
        }
    };
    let mut warnings: Vec<Warning> =
        warning::flipped_acceleration(&acceleration.header, &histories.t, &acceleration.values, v0)
            .into_iter()
            .collect();
    let crush = histories
        .channel(Quantity::Crush)
        .map(|c| c.values.as_slice());
    let (pulse, criteria) = vehicle(
        file,
        &histories.t,
        &acceleration.values,
        v0,
        crush,
        &mut warnings,
    )?;
    Ok(TestMetrics {
        pulse: Some(pulse),
        criteria,
        occupants: Vec::new(),
        pulse_channel: Some(acceleration.header.clone()),
        warnings,
    })
}

fn iso_mme_metrics(test: &Test, request: &MetricsRequest) -> Result<TestMetrics, StudyError> {
    let mut warnings = Vec::new();
    let mut metrics = TestMetrics {
        pulse: None,
        criteria: Criteria::EMPTY,
        occupants: Vec::new(),
        pulse_channel: None,
        warnings: Vec::new(),
    };
    if let Some(channel) = vehicle_acceleration(test) {
        let v0 = match request.v0 {
            Some(v) => v,
            None => impact_velocity(test)?.ok_or_else(|| {
                StudyError::usage(format!(
                    "{}: the test gives no impact velocity (no `Velocity test object 1` and no \
                     vehicle velocity channel); give it with --v0 <m/s>",
                    request.test.display()
                ))
            })?,
        };
        let t = channel.times();
        let a = si_values(channel)?;
        let (pulse, criteria) = vehicle(&request.test, &t, &a, v0, None, &mut warnings)?;
        metrics.pulse = Some(pulse);
        metrics.criteria = criteria;
        metrics.pulse_channel = Some(channel.code.as_str().to_string());
    }
    for occupant in test_data::occupants(test)? {
        let rated = rate(&occupant.measured(), occupant.dummy);
        warnings.extend(rated.warnings.iter().cloned());
        metrics.occupants.push(occupant_criteria(&occupant, rated));
    }
    if let Some(first) = metrics.occupants.first() {
        for rated in &first.criteria.rated {
            metrics.criteria.insert(rated.clone());
        }
        metrics.criteria.dummy = first.criteria.dummy;
    }
    metrics.warnings = warnings;
    Ok(metrics)
}

fn occupant_criteria(occupant: &Occupant, mut criteria: Criteria) -> OccupantCriteria {
    criteria.warnings.clear();
    OccupantCriteria {
        test_object: occupant.test_object.to_string(),
        position: occupant.position.to_string(),
        dummy: occupant.dummy.map(|d: Dummy| d.name().to_string()),
        criteria,
    }
}

/// The impact velocity of a test [m/s]: its `.mme`'s `Velocity test object
/// 1` (in m/s, as ISO-MME gives it), else the first sample of the
/// vehicle's longitudinal velocity channel.
fn impact_velocity(test: &Test) -> Result<Option<f64>, StudyError> {
    if let Some(text) = test.info.get("Velocity test object 1") {
        let v: f64 = text.trim().parse().map_err(|_| {
            StudyError::data_file(format!(
                "{}: Velocity test object 1: `{text}` is not a number",
                test.name
            ))
        })?;
        return Ok(Some(v));
    }
    let velocity = test.channels.iter().find(|c| {
        c.code.main_location() == "VEHC"
            && c.code.dimension() == Dimension::Velocity
            && c.code.direction() == Direction::X
    });
    match velocity {
        Some(channel) => Ok(si_values(channel)?.first().copied()),
        None => Ok(None),
    }
}

/// The pulse metrics of the vehicle's acceleration `a` [m/s²] at times `t`
/// from `v0`, and its criteria (OLC, ASI, ESW, THIV and PHD).
fn vehicle(
    file: &Path,
    t: &[f64],
    a: &[f64],
    v0: f64,
    crush: Option<&[f64]>,
    warnings: &mut Vec<Warning>,
) -> Result<(PulseMetrics, Criteria), StudyError> {
    if !v0.is_finite() {
        return Err(StudyError::usage(format!(
            "impact velocity {v0} is not a number"
        )));
    }
    let evaluation = |e| StudyError::evaluation(format!("{}: {e}", file.display()));
    let pulse = Pulse::resampled(t, a, v0, crush).map_err(evaluation)?;
    let metrics = pulse.metrics().map_err(evaluation)?;
    warnings.extend(pulse.filter_warnings());
    let mut criteria = Criteria::EMPTY;
    let from = vec![file.display().to_string()];
    let mut add = |criterion, value: Option<f64>| {
        if let Some(value) = value {
            criteria.insert(Rated {
                criterion,
                value,
                from: from.clone(),
                when: None,
            });
        }
    };
    add(Criterion::Olc, metrics.olc_g);
    add(Criterion::Asi, metrics.asi);
    add(Criterion::Esw, metrics.equivalent_square_wave_g);
    let dt = pulse.t[1] - pulse.t[0];
    let a180 =
        cfc_filter(&pulse.acceleration, dt, 180.0).unwrap_or_else(|_| pulse.acceleration.clone());
    let v = integrate(&pulse.t, &a180, v0);
    if let Some(hit) = head_impact(&pulse.t, &v, &a180) {
        add(Criterion::Thiv, Some(hit.thiv * 3.6));
        add(Criterion::Phd, hit.phd);
    }
    Ok((metrics, criteria))
}
