//! Which shard a task of an array job is, from the variables its scheduler
//! sets (`--shard auto`).
//!
//! Each scheduler is one entry of [`SCHEDULERS`]: the variable holding the
//! task's index and how to read the index and the number of tasks from it.

use super::plan::{Shard, ShardError};

/// Why a scheduler's variables do not tell the shard of this task.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SchedulerError {
    /// A variable that holds no non-negative integer.
    #[error("{variable}=`{text}` is not a non-negative integer")]
    NotAnInteger {
        /// The variable.
        variable: String,
        /// Its value.
        text: String,
    },
    /// Slurm's task id without the range of the array.
    #[error("SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT must be set with SLURM_ARRAY_TASK_ID")]
    SlurmRangeMissing,
    /// `--shard-count` that is not Slurm's number of tasks.
    #[error("--shard-count {count} differs from SLURM_ARRAY_TASK_COUNT={tasks}")]
    CountDiffers {
        /// `--shard-count`.
        count: usize,
        /// `SLURM_ARRAY_TASK_COUNT`.
        tasks: usize,
    },
    /// A Slurm task id that is not on the array's even steps.
    #[error(
        "task {id} is not one of {tasks} tasks numbered from {min} in steps of {step}; for an uneven --array list give --shard-index K --shard-count N"
    )]
    OffTheArray {
        /// `SLURM_ARRAY_TASK_ID`.
        id: usize,
        /// `SLURM_ARRAY_TASK_COUNT`.
        tasks: usize,
        /// `SLURM_ARRAY_TASK_MIN`.
        min: usize,
        /// `SLURM_ARRAY_TASK_STEP`.
        step: usize,
    },
    /// A scheduler that tells the index only, without `--shard-count`.
    #[error("{variable} gives the task's index; give the number of tasks with --shard-count N")]
    CountNeeded {
        /// The index variable.
        variable: String,
    },
    /// An index and count that make no shard.
    #[error("{0}")]
    Shard(Box<ShardError>),
}

impl From<ShardError> for SchedulerError {
    fn from(e: ShardError) -> SchedulerError {
        SchedulerError::Shard(Box::new(e))
    }
}

/// Looks up an environment variable (`std::env::var` in `lpm`, a table in
/// tests).
pub type Environment<'a> = &'a dyn Fn(&str) -> Option<String>;

/// A scheduler that runs array jobs: the variable that tells a task its
/// index, and how to make a shard of it.
pub struct Scheduler {
    /// The scheduler's name, for messages.
    pub name: &'static str,
    /// The variable set in every task of an array job.
    pub index_variable: &'static str,
    /// The shard of this task; `count` is `--shard-count` if given.
    pub shard: fn(Environment, Option<usize>) -> Result<Shard, SchedulerError>,
}

/// The schedulers `--shard auto` knows, tried in order.
pub const SCHEDULERS: [Scheduler; 3] = [
    Scheduler {
        name: "Slurm",
        index_variable: "SLURM_ARRAY_TASK_ID",
        shard: slurm,
    },
    Scheduler {
        name: "a Kubernetes Indexed Job",
        index_variable: "JOB_COMPLETION_INDEX",
        shard: |env, count| zero_based_index(env, "JOB_COMPLETION_INDEX", count),
    },
    Scheduler {
        name: "AWS Batch",
        index_variable: "AWS_BATCH_JOB_ARRAY_INDEX",
        shard: |env, count| zero_based_index(env, "AWS_BATCH_JOB_ARRAY_INDEX", count),
    },
];

/// The shard of this task from the one scheduler whose index variable is
/// set; `count` (`--shard-count`) is needed where the scheduler does not
/// tell the number of tasks, and checked against it where it does.
pub fn shard_from_environment(env: Environment, count: Option<usize>) -> Result<Shard, ShardError> {
    let present: Vec<&Scheduler> = (SCHEDULERS.iter())
        .filter(|s| env(s.index_variable).is_some())
        .collect();
    match present.as_slice() {
        [scheduler] => (scheduler.shard)(env, count).map_err(|problem| ShardError::Scheduler {
            scheduler: scheduler.name,
            problem,
        }),
        [] => Err(ShardError::NoScheduler {
            variables: SCHEDULERS.iter().map(|s| s.index_variable).collect(),
        }),
        several => Err(ShardError::SeveralSchedulers {
            variables: several.iter().map(|s| s.index_variable).collect(),
        }),
    }
}

/// A non-negative integer variable, by name.
fn integer(env: Environment, name: &str) -> Result<Option<usize>, SchedulerError> {
    match env(name) {
        None => Ok(None),
        Some(text) => text
            .trim()
            .parse()
            .map(Some)
            .map_err(|_| SchedulerError::NotAnInteger {
                variable: name.to_string(),
                text,
            }),
    }
}

/// Slurm numbers array tasks from `SLURM_ARRAY_TASK_MIN` in steps of
/// `SLURM_ARRAY_TASK_STEP` (`--array=1-16`, `--array=0-30:2`) and tells the
/// number of tasks in `SLURM_ARRAY_TASK_COUNT`.
fn slurm(env: Environment, count: Option<usize>) -> Result<Shard, SchedulerError> {
    let id = integer(env, "SLURM_ARRAY_TASK_ID")?.unwrap_or(0);
    let (Some(min), Some(tasks)) = (
        integer(env, "SLURM_ARRAY_TASK_MIN")?,
        integer(env, "SLURM_ARRAY_TASK_COUNT")?,
    ) else {
        return Err(SchedulerError::SlurmRangeMissing);
    };
    let step = integer(env, "SLURM_ARRAY_TASK_STEP")?.unwrap_or(1).max(1);
    if let Some(count) = count
        && count != tasks
    {
        return Err(SchedulerError::CountDiffers { count, tasks });
    }
    let offset = id.checked_sub(min).filter(|o| o % step == 0);
    match offset.map(|o| o / step) {
        Some(index) if index < tasks => Ok(Shard::zero_based(index, tasks)?),
        _ => Err(SchedulerError::OffTheArray {
            id,
            tasks,
            min,
            step,
        }),
    }
}

/// A scheduler that tells a 0-based index but not the number of tasks.
fn zero_based_index(
    env: Environment,
    name: &str,
    count: Option<usize>,
) -> Result<Shard, SchedulerError> {
    let index = integer(env, name)?.unwrap_or(0);
    let count = count.ok_or_else(|| SchedulerError::CountNeeded {
        variable: name.to_string(),
    })?;
    Ok(Shard::zero_based(index, count)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shard of a task whose environment holds `pairs`.
    fn shard(pairs: &[(&str, &str)], count: Option<usize>) -> Result<Shard, String> {
        let env = |name: &str| {
            (pairs.iter())
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        };
        shard_from_environment(&env, count).map_err(|e| e.to_string())
    }

    fn slurm_task(id: &str, min: &str, step: &str, count: &str) -> [(&'static str, String); 4] {
        [
            ("SLURM_ARRAY_TASK_ID", id.to_string()),
            ("SLURM_ARRAY_TASK_MIN", min.to_string()),
            ("SLURM_ARRAY_TASK_STEP", step.to_string()),
            ("SLURM_ARRAY_TASK_COUNT", count.to_string()),
        ]
    }

    fn slurm(
        id: &str,
        min: &str,
        step: &str,
        count: &str,
        shards: Option<usize>,
    ) -> Result<Shard, String> {
        let vars = slurm_task(id, min, step, count);
        let pairs: Vec<(&str, &str)> = vars.iter().map(|(k, v)| (*k, v.as_str())).collect();
        shard(&pairs, shards)
    }

    #[test]
    fn slurm_tasks_map_onto_the_one_based_shards() {
        assert_eq!(
            slurm("1", "1", "1", "16", None),
            Ok(Shard {
                index: 1,
                count: 16
            })
        );
        assert_eq!(
            slurm("16", "1", "1", "16", None),
            Ok(Shard {
                index: 16,
                count: 16
            })
        );
        // --array=0-30:2: task 6 is the fourth of sixteen.
        assert_eq!(
            slurm("6", "0", "2", "16", None),
            Ok(Shard {
                index: 4,
                count: 16
            })
        );
        assert_eq!(
            slurm("6", "0", "2", "16", Some(16)),
            Ok(Shard {
                index: 4,
                count: 16
            })
        );
        let wrong = slurm("6", "0", "2", "16", Some(8)).unwrap_err();
        assert!(
            wrong.contains("--shard-count 8 differs from SLURM_ARRAY_TASK_COUNT=16"),
            "{wrong}"
        );
    }

    #[test]
    fn slurm_ids_off_the_range_are_refused() {
        let odd = slurm("5", "0", "2", "8", None).unwrap_err();
        assert!(
            odd.contains("task 5 is not one of 8 tasks numbered from 0 in steps of 2"),
            "{odd}"
        );
        let beyond = slurm("17", "1", "1", "16", None).unwrap_err();
        assert!(
            beyond.contains("task 17 is not one of 16 tasks"),
            "{beyond}"
        );
        let without_count = shard(&[("SLURM_ARRAY_TASK_ID", "5")], None).unwrap_err();
        assert!(
            without_count.contains("SLURM_ARRAY_TASK_COUNT must be set"),
            "{without_count}"
        );
    }

    #[test]
    fn zero_based_schedulers_need_the_count() {
        assert_eq!(
            shard(&[("JOB_COMPLETION_INDEX", "0")], Some(4)),
            Ok(Shard { index: 1, count: 4 })
        );
        let aws = [("AWS_BATCH_JOB_ARRAY_INDEX", "3")];
        assert_eq!(shard(&aws, Some(4)), Ok(Shard { index: 4, count: 4 }));
        let message = shard(&aws, None).unwrap_err();
        assert!(
            message.contains("AWS Batch") && message.contains("--shard-count N"),
            "{message}"
        );
        let beyond = shard(&aws, Some(3)).unwrap_err();
        assert!(beyond.contains("index 3"), "{beyond}");
        let text = shard(&[("JOB_COMPLETION_INDEX", "two")], Some(4)).unwrap_err();
        assert!(
            text.contains("JOB_COMPLETION_INDEX=`two` is not a non-negative integer"),
            "{text}"
        );
    }

    #[test]
    fn no_scheduler_or_several_are_errors_that_say_what_to_do() {
        let none = shard(&[], Some(4)).unwrap_err();
        assert!(
            none.contains("SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX, AWS_BATCH_JOB_ARRAY_INDEX"),
            "{none}"
        );
        let both = [
            ("JOB_COMPLETION_INDEX", "0"),
            ("AWS_BATCH_JOB_ARRAY_INDEX", "1"),
        ];
        let both = shard(&both, Some(4)).unwrap_err();
        assert!(
            both.contains("JOB_COMPLETION_INDEX and AWS_BATCH_JOB_ARRAY_INDEX are all set"),
            "{both}"
        );
    }
}
