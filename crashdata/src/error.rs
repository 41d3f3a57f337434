//! The errors of the crate, each carrying where it happened as data: the
//! field of a channel code, the file, line and field of a test.

use std::fmt;
use std::path::{Path, PathBuf};

/// A field of the 16-character channel code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CodeField {
    /// Position 1.
    TestObject,
    /// Position 2.
    Position,
    /// Positions 3–6.
    MainLocation,
    /// Positions 7–8.
    FineLocation1,
    /// Positions 9–10.
    FineLocation2,
    /// Positions 11–12.
    FineLocation3,
    /// Positions 13–14.
    Dimension,
    /// Position 15.
    Direction,
    /// Position 16.
    FilterClass,
}

impl CodeField {
    /// The field at character `k` of a code (from 0; 15 and beyond: the
    /// filter class).
    pub fn at(k: usize) -> CodeField {
        match k {
            0 => CodeField::TestObject,
            1 => CodeField::Position,
            2..=5 => CodeField::MainLocation,
            6..=7 => CodeField::FineLocation1,
            8..=9 => CodeField::FineLocation2,
            10..=11 => CodeField::FineLocation3,
            12..=13 => CodeField::Dimension,
            14 => CodeField::Direction,
            _ => CodeField::FilterClass,
        }
    }

    /// The characters of the code it takes (from 0).
    pub fn range(self) -> std::ops::Range<usize> {
        match self {
            CodeField::TestObject => 0..1,
            CodeField::Position => 1..2,
            CodeField::MainLocation => 2..6,
            CodeField::FineLocation1 => 6..8,
            CodeField::FineLocation2 => 8..10,
            CodeField::FineLocation3 => 10..12,
            CodeField::Dimension => 12..14,
            CodeField::Direction => 14..15,
            CodeField::FilterClass => 15..16,
        }
    }
}

impl fmt::Display for CodeField {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(match self {
            CodeField::TestObject => "test object",
            CodeField::Position => "position",
            CodeField::MainLocation => "main location",
            CodeField::FineLocation1 => "fine location 1",
            CodeField::FineLocation2 => "fine location 2",
            CodeField::FineLocation3 => "fine location 3",
            CodeField::Dimension => "physical dimension",
            CodeField::Direction => "direction",
            CodeField::FilterClass => "filter class",
        })
    }
}

/// A channel code that is not one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CodeError {
    /// Not 16 characters.
    #[error("channel code \"{code}\" has {length} characters; a channel code has 16")]
    Length {
        /// The text read.
        code: String,
        /// How many characters it has.
        length: usize,
    },
    /// A field outside its table.
    #[error(
        "channel code \"{code}\": the {field} (position {position}) is \"{found}\"; expected {expected}"
    )]
    Field {
        /// The text read.
        code: String,
        /// The position (from 1) of the first character that does not fit.
        position: usize,
        /// The field it is in.
        field: CodeField,
        /// The field's characters as found.
        found: String,
        /// What the field takes.
        expected: &'static str,
    },
}

/// A test that cannot be read: the file, the line (from 1) and the field
/// where it is known, and what is wrong.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}{}{problem}", place(file, *line), field.as_ref().map_or(String::new(), |f| format!("{f}: ")))]
pub struct ReadError {
    /// The file (a member of a zip is `ARCHIVE.zip/MEMBER`).
    pub file: PathBuf,
    /// The line of the file, from 1.
    pub line: Option<usize>,
    /// The header field (`Number of samples`), or what else the line
    /// holds (`sample 12`).
    pub field: Option<String>,
    /// What is wrong.
    pub problem: String,
}

impl ReadError {
    /// A problem with `file` as a whole.
    pub fn file(file: &Path, problem: impl Into<String>) -> ReadError {
        ReadError {
            file: file.to_path_buf(),
            line: None,
            field: None,
            problem: problem.into(),
        }
    }

    /// A problem with `field` at `line` of `file`.
    pub fn at(
        file: &Path,
        line: Option<usize>,
        field: impl Into<String>,
        problem: impl Into<String>,
    ) -> ReadError {
        ReadError {
            file: file.to_path_buf(),
            line,
            field: Some(field.into()),
            problem: problem.into(),
        }
    }
}

/// `file:line: ` (`file: ` without a line).
fn place(file: &Path, line: Option<usize>) -> String {
    match line {
        Some(line) => format!("{}:{line}: ", file.display()),
        None => format!("{}: ", file.display()),
    }
}

/// A test that cannot be written; nothing of it is left behind.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The disk refused: creating, writing or renaming `path`.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A channel that cannot be written as given.
    #[error("channel {index} ({code}): {problem}")]
    Channel {
        /// Its number in the test, from 1.
        index: usize,
        /// Its code.
        code: String,
        /// What is wrong (no samples, a sampling interval that is not
        /// positive).
        problem: String,
    },
    /// A test name that cannot be a file name.
    #[error("test name \"{0}\" cannot name a file (empty, or with a path separator)")]
    Name(String),
}
