//! `lpm generate`: write (or check) the committed generated files.

use crate::failure::{Failure, Outcome};
use crate::status::ExitStatus;
use lagrangian_core::generate::{GenerateError, generate_all, stale};
use lagrangian_sim::report::write_atomically;
use std::path::PathBuf;

/// Options of `lpm generate`.
#[derive(clap::Args)]
pub struct Args {
    /// The workspace root (with specs/ and generated/).
    #[arg(long, default_value = ".")]
    root: PathBuf,
    /// List the stale files (status 6) instead of writing them.
    #[arg(long)]
    check: bool,
}

/// A failure of the generator: a spec's rendered diagnostics, or a file.
fn failure(e: GenerateError) -> Failure {
    match e {
        GenerateError::Spec { .. } => Failure::rendered(ExitStatus::Spec, e.to_string()),
        GenerateError::Read { .. } => Failure::new(ExitStatus::Spec, e.to_string()),
    }
}

/// Runs `lpm generate`.
pub fn run(args: Args) -> Result<Outcome, Failure> {
    let root = &args.root;
    if args.check {
        let files = stale(root).map_err(failure)?;
        if files.is_empty() {
            return Ok(Outcome::success(
                "generated files are up to date\n".to_string(),
            ));
        }
        let list: Vec<String> = files.iter().map(|p| format!("  {}", p.display())).collect();
        return Ok(Outcome {
            text: format!(
                "stale generated files (run `cargo generate`):\n{}\n",
                list.join("\n")
            ),
            status: ExitStatus::Stale,
        });
    }
    let files = generate_all(root).map_err(failure)?;
    let mut written = 0;
    for file in &files {
        let path = root.join(&file.path);
        if std::fs::read_to_string(&path).ok().as_deref() == Some(file.contents.as_str()) {
            continue;
        }
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)
                .map_err(|e| Failure::io(format!("cannot create {}: {e}", dir.display())))?;
        }
        write_atomically(&path, file.contents.as_bytes())
            .map_err(|e| Failure::io(format!("cannot write {}: {e}", path.display())))?;
        written += 1;
    }
    Ok(Outcome::success(format!(
        "{} generated files, {written} rewritten\n",
        files.len()
    )))
}
