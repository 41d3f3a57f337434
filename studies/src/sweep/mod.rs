//! Ensembles: one scenario run many times with some of its values varied —
//! over a full-factorial grid or a sampled design — in parallel, one output
//! row of summary metrics per run.
//!
//! A run's values depend only on the plan and the run's index, so a sweep
//! can be split into [`Shard`]s computed anywhere (a Slurm job array, a
//! Kubernetes Indexed Job, GNU parallel) whose tables, merged by
//! [`merged_rows`], are the full sweep.

mod envelope;
mod envelope_file;
mod envelope_table;
mod exact_sum;
mod journal;
mod merge;
mod plan;
mod run;
mod scheduler;
mod shared;
mod table;
mod weights;

pub use envelope::{
    Accumulated, ChannelEnvelope, Envelope, EnvelopeError, EnvelopeJob, History, Times,
    stream_envelope,
};
pub use envelope_file::{
    ENVELOPE_FORMAT, ENVELOPE_VERSION, EnvelopeFileError, FileProblem, MarkDifference,
    PartialEnvelope, SweepMark, merged_envelope, partial_envelope_path,
};
pub use envelope_table::{envelope_columns, write_envelope_csv, write_envelope_parquet};
pub use exact_sum::ExactSum;
pub use journal::{Journal, JournalError, LineProblem, journal_path, read_groups};
pub use merge::{Location, MergeError, MissingRuns, RowProblem, merged_rows};
pub use plan::{Assignment, Axis, Design, Plan, PlanError, SampledAxis, Shard, ShardError};
pub use run::{
    Row, RunFailure, Settings, SettingsError, SweepJob, run_scenario, run_sweep, stream_sweep,
};
pub use scheduler::{Environment, SCHEDULERS, Scheduler, SchedulerError, shard_from_environment};
pub use table::{
    Layout, RecordError, WriteError, columns, parse_record, record, sweep_csv, sweep_parquet,
    write_csv, write_parquet,
};
pub use weights::{WeightOf, Weights, WeightsError, WeightsProblem};
