//! Writing the FMU's zip archive atomically: into a temporary file beside
//! the target, renamed over it only once complete, so that a failed
//! export never leaves a half-written FMU.

use lagrangian_studies::error::StudyError;
use std::io::Write;
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;

/// Why the archive was not written (nothing is left of it).
#[derive(Debug, thiserror::Error)]
pub enum ArchiveError {
    /// The temporary file cannot be created.
    #[error("cannot create {}: {error}", .path.display())]
    Create {
        /// The temporary file.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// The temporary file cannot be written (by the zip writer, or to the
    /// disk).
    #[error("cannot write {}: {error}", .path.display())]
    Write {
        /// The temporary file.
        path: PathBuf,
        /// Why: the zip writer's error or the file system's.
        error: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The complete archive cannot be renamed over the target.
    #[error("cannot move {} to {}: {error}", .from.display(), .to.display())]
    Move {
        /// The temporary file.
        from: PathBuf,
        /// The target.
        to: PathBuf,
        /// Why.
        error: std::io::Error,
    },
}

/// A file that cannot be written, as every service of the studies says it.
impl From<ArchiveError> for StudyError {
    fn from(e: ArchiveError) -> StudyError {
        StudyError::io(e.to_string())
    }
}

/// One file of the archive: its path inside (with `/`) and its bytes.
pub struct Entry {
    /// The path inside the archive.
    pub name: String,
    /// The contents.
    pub bytes: Vec<u8>,
    /// Whether the file is executable (the shared library).
    pub executable: bool,
}

/// Writes `entries` (deflated) as the zip file `out`, atomically.
pub fn write_atomically(out: &Path, entries: &[Entry]) -> Result<(), ArchiveError> {
    let temporary = temporary_beside(out);
    let result = write_zip(&temporary, entries).and_then(|()| {
        std::fs::rename(&temporary, out).map_err(|error| ArchiveError::Move {
            from: temporary.clone(),
            to: out.to_path_buf(),
            error,
        })
    });
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result
}

/// `.NAME.tmp-PID` beside `out`: on the same file system, so the rename
/// is atomic.
fn temporary_beside(out: &Path) -> PathBuf {
    let name = out
        .file_name()
        .map_or("fmu".into(), |n| n.to_string_lossy().into_owned());
    out.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

fn write_zip(path: &Path, entries: &[Entry]) -> Result<(), ArchiveError> {
    let file = std::fs::File::create(path).map_err(|error| ArchiveError::Create {
        path: path.to_path_buf(),
        error,
    })?;
    let mut zip = zip::ZipWriter::new(file);
    let failed = |error: Box<dyn std::error::Error + Send + Sync>| ArchiveError::Write {
        path: path.to_path_buf(),
        error,
    };
    for entry in entries {
        let mode = if entry.executable { 0o755 } else { 0o644 };
        let options = SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .unix_permissions(mode);
        zip.start_file(entry.name.as_str(), options)
            .map_err(|e| failed(e.into()))?;
        zip.write_all(&entry.bytes).map_err(|e| failed(e.into()))?;
    }
    let file = zip.finish().map_err(|e| failed(e.into()))?;
    file.sync_all().map_err(|e| failed(e.into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_archive_is_written_whole_or_not_at_all() {
        let dir = std::env::temp_dir().join(format!("lpm-archive-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("a.fmu");
        let entries = [Entry {
            name: "resources/x.txt".to_string(),
            bytes: b"hello".to_vec(),
            executable: false,
        }];
        write_atomically(&out, &entries).unwrap();
        let mut archive = zip::ZipArchive::new(std::fs::File::open(&out).unwrap()).unwrap();
        let mut text = String::new();
        std::io::Read::read_to_string(&mut archive.by_name("resources/x.txt").unwrap(), &mut text)
            .unwrap();
        assert_eq!(text, "hello");
        // Into a folder that does not exist: an error, and nothing left.
        let missing = dir.join("no/such/dir/b.fmu");
        let refused = write_atomically(&missing, &entries).unwrap_err();
        let beside = missing.parent().unwrap();
        assert!(
            matches!(&refused, ArchiveError::Create { path, .. } if path.parent() == Some(beside)),
            "{refused}"
        );
        assert!(
            refused.to_string().starts_with("cannot create "),
            "{refused}"
        );
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left, [std::ffi::OsString::from("a.fmu")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
