//! `lpm generate`: write (or check) the committed generated files.

use crate::commands::Failure;
use lagrangian_core::generate::{generate_all, stale};
use lagrangian_sim::report::write_atomically;
use std::path::Path;

/// Exit status when `--check` finds stale files.
pub const STALE: u8 = crate::commands::status::STALE;

pub fn run(root: &Path, check: bool) -> Result<(String, u8), Failure> {
    if check {
        let files = stale(root).map_err(|e| Failure::spec(format!("error: {e}")))?;
        if files.is_empty() {
            return Ok(("generated files are up to date\n".to_string(), 0));
        }
        let list: Vec<String> = files.iter().map(|p| format!("  {}", p.display())).collect();
        return Ok((
            format!(
                "stale generated files (run `cargo generate`):\n{}\n",
                list.join("\n")
            ),
            STALE,
        ));
    }
    let files = generate_all(root).map_err(|e| Failure::spec(format!("error: {e}")))?;
    let mut written = 0;
    for file in &files {
        let path = root.join(&file.path);
        if std::fs::read_to_string(&path).ok().as_deref() == Some(file.contents.as_str()) {
            continue;
        }
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)
                .map_err(|e| Failure::io(format!("error: cannot create {}: {e}", dir.display())))?;
        }
        write_atomically(&path, file.contents.as_bytes())
            .map_err(|e| Failure::io(format!("error: cannot write {}: {e}", path.display())))?;
        written += 1;
    }
    Ok((
        format!("{} generated files, {written} rewritten\n", files.len()),
        0,
    ))
}
