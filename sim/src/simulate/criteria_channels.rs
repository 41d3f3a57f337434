//! The records of the occupant channels a scenario names with a dummy's
//! ISO-MME codes (`[iso_mme.channels]`), and their injury criteria at the
//! end of the run ([`crate::criteria`]).

use crate::criteria::codes::{dummy_of, filtered_at, placement};
use crate::criteria::occupant::{Body, Measure};
use crate::criteria::{Criteria, Dummy, Measured, rate};
use crate::pulse::Pulse;
use crate::scenario::{Columns, Scenario, Signal};

/// One occupant channel: what it records and where a criterion reads it.
#[derive(Clone, Debug)]
struct Record {
    code: String,
    signal: Signal,
    body: Body,
    measure: Measure,
    filtered: Option<f64>,
    values: Vec<f64>,
}

/// The occupant channels of a run, sample by sample.
#[derive(Clone, Debug)]
pub(super) struct CriteriaRecords {
    records: Vec<Record>,
    dummy: Option<Dummy>,
}

impl CriteriaRecords {
    /// The records of `scenario`'s channels that a criterion reads.
    pub(super) fn new(scenario: &Scenario, samples: usize) -> CriteriaRecords {
        let placed = scenario.iso_mme.channels.iter().filter_map(|c| {
            let (body, measure) = placement(&c.code)?;
            Some(Record {
                code: c.code.as_str().to_string(),
                signal: c.signal.clone(),
                body,
                measure,
                filtered: filtered_at(&c.code),
                values: Vec::with_capacity(samples),
            })
        });
        let records: Vec<Record> = placed.collect();
        let dummy = (scenario.iso_mme.channels.iter())
            .filter(|c| placement(&c.code).is_some())
            .find_map(|c| dummy_of(&c.code));
        CriteriaRecords { records, dummy }
    }

    /// Takes the next sample's columns.
    pub(super) fn push(&mut self, columns: &Columns) {
        for record in &mut self.records {
            record.values.push(record.signal.value(columns));
        }
    }

    /// Whether there is no channel to rate.
    pub(super) fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// The criteria of the records taken at `times`, each record put on the
    /// even grid of the smallest period first (events add samples between
    /// the output times).
    pub(super) fn criteria(&self, times: &[f64]) -> Criteria {
        let even: Vec<Option<Pulse>> = (self.records.iter())
            .map(|r| Pulse::resampled(times, &r.values, 0.0, None).ok())
            .collect();
        let measured: Vec<Measured> = (self.records.iter().zip(&even))
            .filter_map(|(r, pulse)| {
                let pulse = pulse.as_ref()?;
                Some(Measured {
                    name: &r.code,
                    body: r.body,
                    measure: r.measure,
                    t0: pulse.t[0],
                    dt: pulse.t[1] - pulse.t[0],
                    values: &pulse.acceleration,
                    filtered: r.filtered,
                })
            })
            .collect();
        rate(&measured, self.dummy)
    }
}
