//! What `simulate` and `metrics` do with the warnings of a run or a pulse:
//! print each on stderr, and under `--strict` end with an exit status of
//! their own.

use crate::failure::Outcome;
use crate::status::ExitStatus;
use lagrangian_sim::warning::Warning;

/// The outcome of a command that printed `text` and found `warnings`: each
/// is printed on stderr as `warning: …`; under `strict`, a command with
/// warnings ends with [`ExitStatus::Warnings`] (its outputs are written, so
/// that they can be looked at).
pub fn outcome(text: String, warnings: &[Warning], strict: bool) -> Outcome {
    for warning in warnings {
        eprintln!("warning: {warning}");
    }
    let status = if strict && !warnings.is_empty() {
        eprintln!("error: --strict: {} warning(s), see above", warnings.len());
        ExitStatus::Warnings
    } else {
        ExitStatus::Success
    };
    Outcome { text, status }
}
