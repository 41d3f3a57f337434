//! Where a host's files come from: the specs, scenarios and CSV tables a
//! run reads. A host chooses: [`Disk`] reads every time; [`Cached`] also
//! reads every time, but parses a table again only when its text changed,
//! which a sweep or a fit — the same scenario resolved once per run —
//! would otherwise do for every run. Another implementation (files held in
//! memory, say) is one `impl Files`.

use crate::table::{Table, TableError};
use std::collections::HashMap;
use std::fmt::Debug;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The files a host reads. Shared by a sweep's worker threads, hence
/// `Sync` and `&self`.
pub trait Files: Debug + Send + Sync {
    /// The text of the file at `path`.
    fn text(&self, path: &Path) -> std::io::Result<Arc<str>>;

    /// The CSV table at `path` (see [`Table::parse`]).
    fn table(&self, path: &Path) -> Result<Arc<Table>, TableError> {
        let text = self.text(path).map_err(|e| unreadable(path, &e))?;
        Table::parse(path, &text).map(Arc::new)
    }
}

/// The files as they are on disk, read and parsed at every call.
#[derive(Clone, Copy, Debug, Default)]
pub struct Disk;

impl Files for Disk {
    fn text(&self, path: &Path) -> std::io::Result<Arc<str>> {
        std::fs::read_to_string(path).map(Arc::from)
    }
}

/// The files on disk, each table parsed once per text: a call reads the
/// file again (so an edit between two calls is seen) and parses it only
/// when its text differs from the one parsed last time.
#[derive(Debug, Default)]
pub struct Cached {
    tables: Mutex<HashMap<PathBuf, Parsed>>,
}

/// A table with the text it was parsed from.
#[derive(Debug)]
struct Parsed {
    text: Arc<str>,
    table: Arc<Table>,
}

impl Files for Cached {
    fn text(&self, path: &Path) -> std::io::Result<Arc<str>> {
        Disk.text(path)
    }

    fn table(&self, path: &Path) -> Result<Arc<Table>, TableError> {
        let text = self.text(path).map_err(|e| unreadable(path, &e))?;
        let mut tables = self.tables.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(parsed) = tables.get(path)
            && *parsed.text == *text
        {
            return Ok(Arc::clone(&parsed.table));
        }
        let table = Arc::new(Table::parse(path, &text)?);
        let parsed = Parsed {
            text,
            table: Arc::clone(&table),
        };
        tables.insert(path.to_path_buf(), parsed);
        Ok(table)
    }
}

/// The table error of a file that cannot be read.
fn unreadable(path: &Path, e: &std::io::Error) -> TableError {
    TableError::Read {
        file: path.to_path_buf(),
        message: e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("lpm-files-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_cached_table_is_parsed_again_only_when_its_text_changes() {
        let path = folder("cached").join("forces.csv");
        std::fs::write(&path, "t,F\n0,1\n1,2\n").unwrap();
        let files = Cached::default();
        let first = files.table(&path).unwrap();
        let again = files.table(&path).unwrap();
        assert!(
            Arc::ptr_eq(&first, &again),
            "unchanged text: the same table"
        );
        std::fs::write(&path, "t,F\n0,1\n1,3\n").unwrap();
        let edited = files.table(&path).unwrap();
        assert!(!Arc::ptr_eq(&first, &edited));
        let at_end = |table: &Table| {
            let curve = table.curve("t", "F", crate::curve::Outside::Hold).unwrap();
            curve.eval(1.0).unwrap().0
        };
        assert_eq!((at_end(&first), at_end(&edited)), (2.0, 3.0));
    }

    #[test]
    fn disk_and_cached_report_a_missing_file_alike() {
        let path = folder("missing").join("none.csv");
        let disk = Disk.table(&path).unwrap_err();
        let cached = Cached::default().table(&path).unwrap_err();
        assert_eq!(disk, cached);
        assert!(disk.to_string().starts_with(&path.display().to_string()));
    }
}
