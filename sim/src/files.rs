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

    /// Files held in memory, which counts the tables asked for.
    #[derive(Debug, Default)]
    struct Memory {
        texts: HashMap<PathBuf, &'static str>,
        tables_asked: std::sync::atomic::AtomicUsize,
    }

    impl Files for Memory {
        fn text(&self, path: &Path) -> std::io::Result<Arc<str>> {
            let missing = || std::io::Error::from(std::io::ErrorKind::NotFound);
            self.texts
                .get(path)
                .map(|t| Arc::from(*t))
                .ok_or_else(missing)
        }

        fn table(&self, path: &Path) -> Result<Arc<Table>, TableError> {
            (self.tables_asked).fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let text = self.text(path).map_err(|e| unreadable(path, &e))?;
            Table::parse(path, &text).map(Arc::new)
        }
    }

    #[test]
    fn a_scenario_reads_itself_and_its_tables_from_the_hosts_files() {
        use crate::scenario::{BaseScenario, ModelNames, Override, Scenario};
        let spec = include_str!("../../specs/spring_mass_damper.lpm");
        let names = ModelNames::of_interpreted(&lagrangian_core::interpret(spec).unwrap());
        let folder = Path::new("/nowhere-on-disk");
        let scenario =
            "[components.b]\ntype = \"table\"\nfile = \"forces.csv\"\ncolumns = { push = \"F\" }\n";
        let memory = Memory {
            texts: HashMap::from([
                (folder.join("s.toml"), scenario),
                (folder.join("forces.csv"), "t,F\n0,5\n1,100\n"),
            ]),
            ..Memory::default()
        };
        let path = folder.join("s.toml");
        Scenario::read(&memory, &path, &names, &[]).unwrap();
        let on_disk = Scenario::read(&Disk, &path, &names, &[]).unwrap_err();
        assert!(on_disk.to_string().contains("cannot read"), "{on_disk}");
        // Every run of a study resolves its base scenario through them.
        let memory = Arc::new(memory);
        let base = BaseScenario {
            text: scenario.into(),
            file: Some(path),
            names,
            settings: Vec::new(),
            files: Arc::clone(&memory) as Arc<dyn Files>,
        };
        for m in [1.0, 2.0, 3.0] {
            base.resolve(&[Override::number("m", m)]).unwrap();
        }
        let asked = memory
            .tables_asked
            .load(std::sync::atomic::Ordering::Relaxed);
        assert_eq!(asked, 4);
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
