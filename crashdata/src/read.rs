//! Reading an ISO-MME test from a folder (holding one `.mme`), an `.mme`
//! path or a `.zip` (with the `zip` feature).
//!
//! What is checked, each failure naming the file, line and field: every
//! line of the `.mme` and `.chn` is `Name:value`; the `.chn` gives `Number
//! of channels` and `Name of channel NNN` for each, with a valid code; each
//! channel file `Channel/<test>.NNN` exists (names compared without case,
//! as on Windows, where most tests are written), repeats the code of its
//! `.chn` line, gives `Sampling interval` (positive), `Time of first
//! sample` and `Number of samples`, and holds that many samples, one number
//! (or `NOVALUE`, read as NaN) a line. An explicit time channel
//! (`Reference channel: explicit`) is refused: the time base read is the
//! implicit one, `t = t0 + i·dt`.

use crate::code::ChannelCode;
use crate::error::ReadError;
use crate::test::{Channel, Test};
use crate::text::{Entry, Header, decode, entry_of};
use std::path::{Path, PathBuf};

/// Reads the test at `path`: a folder holding one `.mme` (in it or below
/// it), an `.mme` file, or a `.zip` of a test.
pub fn read(path: &Path) -> Result<Test, ReadError> {
    let source = Source::open(path)?;
    let mme = source.the_mme(path)?;
    read_test(&source, mme)
}

/// The files of a test: a folder's, or a zip's members.
struct Source {
    /// Where the files are: a folder, or the zip (its members are shown
    /// as `ARCHIVE.zip/MEMBER`).
    root: PathBuf,
    /// Each file's path below `root` (`/`-separated) and where its bytes are.
    files: Vec<(String, Bytes)>,
    /// Whether `root` is a zip.
    zipped: bool,
}

/// Where a file's bytes are.
enum Bytes {
    /// On the disk.
    Disk(PathBuf),
    /// Read from a zip.
    #[cfg(feature = "zip")]
    Held(Vec<u8>),
}

/// How deep below a folder its `.mme` is looked for.
const MAX_DEPTH: usize = 4;

impl Source {
    /// The files of the test at `path` (see [`read`]).
    fn open(path: &Path) -> Result<Source, ReadError> {
        let extension = (path.extension().and_then(|e| e.to_str()))
            .map(str::to_ascii_lowercase)
            .unwrap_or_default();
        if path.is_dir() {
            return Source::folder(path.to_path_buf());
        }
        if !path.exists() {
            return Err(ReadError::file(path, "no such file or folder"));
        }
        match extension.as_str() {
            "mme" => Source::folder(path.parent().unwrap_or(Path::new(".")).to_path_buf()),
            "zip" => Source::zip(path),
            _ => Err(ReadError::file(
                path,
                "not an ISO-MME test: give a folder, an .mme file or a .zip",
            )),
        }
    }

    /// The files below folder `root`, [`MAX_DEPTH`] levels deep.
    fn folder(root: PathBuf) -> Result<Source, ReadError> {
        let mut files = Vec::new();
        let mut pending = vec![(root.clone(), String::new(), 0)];
        while let Some((dir, prefix, depth)) = pending.pop() {
            let listing = std::fs::read_dir(&dir)
                .map_err(|e| ReadError::file(&dir, format!("cannot list: {e}")))?;
            for item in listing {
                let item = item.map_err(|e| ReadError::file(&dir, format!("cannot list: {e}")))?;
                let name = format!("{prefix}{}", item.file_name().to_string_lossy());
                let path = item.path();
                if path.is_dir() && depth < MAX_DEPTH {
                    pending.push((path, format!("{name}/"), depth + 1));
                } else if path.is_file() {
                    files.push((name, Bytes::Disk(path)));
                }
            }
        }
        files.sort_by(|a, b| a.0.cmp(&b.0));
        Ok(Source {
            root,
            files,
            zipped: false,
        })
    }

    /// The members of the zip at `path`, read into memory.
    #[cfg(feature = "zip")]
    fn zip(path: &Path) -> Result<Source, ReadError> {
        use std::io::Read;
        let unreadable =
            |e: &dyn std::fmt::Display| ReadError::file(path, format!("not a readable zip: {e}"));
        let file = std::fs::File::open(path).map_err(|e| unreadable(&e))?;
        let mut archive = zip::ZipArchive::new(file).map_err(|e| unreadable(&e))?;
        let mut files = Vec::new();
        for k in 0..archive.len() {
            let mut member = archive.by_index(k).map_err(|e| unreadable(&e))?;
            if member.is_dir() {
                continue;
            }
            let name = member.name().trim_start_matches('/').to_string();
            let mut bytes = Vec::new();
            member
                .read_to_end(&mut bytes)
                .map_err(|e| ReadError::file(&path.join(&name), format!("cannot unzip: {e}")))?;
            files.push((name, Bytes::Held(bytes)));
        }
        Ok(Source {
            root: path.to_path_buf(),
            files,
            zipped: true,
        })
    }

    /// Without the `zip` feature a zip is refused.
    #[cfg(not(feature = "zip"))]
    fn zip(path: &Path) -> Result<Source, ReadError> {
        Err(ReadError::file(
            path,
            "zipped tests need lagrangian-crashdata's `zip` feature",
        ))
    }

    /// The `.mme` of the test: the one `path` names, else the only one.
    fn the_mme(&self, path: &Path) -> Result<usize, ReadError> {
        if path.is_file() && !self.zipped {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            return (self.files.iter())
                .position(|(n, _)| Some(n) == name.as_ref())
                .ok_or_else(|| ReadError::file(path, "cannot list its folder"));
        }
        let mmes: Vec<usize> = (0..self.files.len())
            .filter(|&k| has_extension(&self.files[k].0, "mme"))
            .collect();
        match mmes.as_slice() {
            [one] => Ok(*one),
            [] => Err(ReadError::file(
                path,
                "holds no .mme file: not an ISO-MME test",
            )),
            many => Err(ReadError::file(
                path,
                format!(
                    "holds {} .mme files ({}); give the path of the one to read",
                    many.len(),
                    (many.iter().map(|&k| self.files[k].0.as_str()))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )),
        }
    }

    /// The file `name` (below the root; compared without case).
    fn find(&self, name: &str) -> Option<usize> {
        let wanted = name.to_lowercase();
        (self.files.iter()).position(|(n, _)| n.to_lowercase() == wanted)
    }

    /// How messages name file `k`.
    fn shown(&self, k: usize) -> PathBuf {
        self.root.join(&self.files[k].0)
    }

    /// The text of file `k`.
    fn text(&self, k: usize) -> Result<String, ReadError> {
        match &self.files[k].1 {
            Bytes::Disk(path) => std::fs::read(path)
                .map(|bytes| decode(&bytes))
                .map_err(|e| ReadError::file(path, format!("cannot read: {e}"))),
            #[cfg(feature = "zip")]
            Bytes::Held(bytes) => Ok(decode(bytes)),
        }
    }
}

/// Whether file `name` ends in `.EXTENSION` (without case).
fn has_extension(name: &str, extension: &str) -> bool {
    (name.rsplit_once('.')).is_some_and(|(_, e)| e.eq_ignore_ascii_case(extension))
}

/// The test whose `.mme` is file `mme` of `source`.
fn read_test(source: &Source, mme: usize) -> Result<Test, ReadError> {
    let mme_name = &source.files[mme].0;
    let (folder, file_name) = match mme_name.rsplit_once('/') {
        Some((folder, file)) => (format!("{folder}/"), file),
        None => (String::new(), mme_name.as_str()),
    };
    let name = file_name[..file_name.len() - ".mme".len()].to_string();
    let info = all_entries(&source.text(mme)?, &source.shown(mme))?;
    let chn_name = format!("{folder}Channel/{name}.chn");
    let Some(chn) = source.find(&chn_name) else {
        return Ok(Test {
            name,
            info,
            channel_info: Header::new(),
            channels: Vec::new(),
        });
    };
    let chn_file = source.shown(chn);
    let chn_text = source.text(chn)?;
    let channel_info = all_entries(&chn_text, &chn_file)?;
    let listed = channel_list(&chn_text, &chn_file)?;
    let mut channels = Vec::with_capacity(listed.len());
    for entry in listed {
        let file_name = format!("{folder}Channel/{name}.{}", entry.number);
        let Some(k) = source.find(&file_name) else {
            return Err(ReadError::file(
                &source.root.join(&file_name),
                format!(
                    "missing: {} lists it (line {}, Name of channel {})",
                    chn_file.display(),
                    entry.line,
                    entry.number
                ),
            ));
        };
        channels.push(read_channel(&source.text(k)?, &source.shown(k), &entry)?);
    }
    Ok(Test {
        name,
        info,
        channel_info,
        channels,
    })
}

/// Every line of `text` (blank lines aside) as `Name:value`; a line that
/// is not one is an error at its line.
fn all_entries(text: &str, file: &Path) -> Result<Header, ReadError> {
    let mut entries = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        match entry_of(line) {
            Some(entry) => entries.push(entry),
            None => {
                return Err(ReadError {
                    file: file.to_path_buf(),
                    line: Some(k + 1),
                    field: None,
                    problem: format!("\"{}\" is not a `Name:value` line", line.trim()),
                });
            }
        }
    }
    Ok(entries.into_iter().collect())
}

/// The `Name:value` lines of `text` with their line numbers (from 1).
fn numbered_entries(text: &str) -> impl Iterator<Item = (usize, Entry)> + '_ {
    (text.lines().enumerate()).filter_map(|(k, line)| Some((k + 1, entry_of(line)?)))
}

/// A channel as the `.chn` lists it.
struct Listed {
    /// The number as written (`001`).
    number: String,
    /// Its line in the `.chn`.
    line: usize,
    /// Its code.
    code: ChannelCode,
}

/// The channels a `.chn` lists: `Number of channels`, and `Name of channel
/// NNN: CODE[ / description]` for each of 1 to that number.
fn channel_list(text: &str, file: &Path) -> Result<Vec<Listed>, ReadError> {
    const COUNT: &str = "Number of channels";
    const PREFIX: &str = "Name of channel ";
    let entries: Vec<(usize, Entry)> = numbered_entries(text).collect();
    let Some((count_line, count)) = entries.iter().find(|(_, e)| e.name == COUNT) else {
        return Err(missing(file, COUNT, "a .chn must give it"));
    };
    let count: usize = whole_number(file, *count_line, count)?;
    let mut listed: Vec<Option<Listed>> = (0..count).map(|_| None).collect();
    for (line, entry) in &entries {
        let Some(number) = entry.name.strip_prefix(PREFIX) else {
            continue;
        };
        let at = |problem: String| ReadError::at(file, Some(*line), &entry.name, problem);
        let index = (number.trim().parse::<usize>().ok())
            .filter(|&i| (1..=count).contains(&i))
            .ok_or_else(|| {
                at(format!(
                    "not a channel number from 1 to {count} (Number of channels)"
                ))
            })?;
        let value = entry.value.as_deref().unwrap_or_default();
        let code_text = value.split(['/', ' ', '\t']).next().unwrap_or_default();
        let code = ChannelCode::parse(code_text).map_err(|e| at(e.to_string()))?;
        if listed[index - 1].is_some() {
            return Err(at(format!("channel {index} is listed twice")));
        }
        listed[index - 1] = Some(Listed {
            number: number.trim().to_string(),
            line: *line,
            code,
        });
    }
    (listed.into_iter().enumerate())
        .map(|(k, l)| {
            l.ok_or_else(|| {
                let field = format!("{PREFIX}{:03}", k + 1);
                missing(file, &field, &format!("Number of channels is {count}"))
            })
        })
        .collect()
}

/// A field that is not there.
fn missing(file: &Path, field: &str, why: &str) -> ReadError {
    ReadError::at(file, None, field, format!("missing ({why})"))
}

/// The value of `entry` as a whole number.
fn whole_number(file: &Path, line: usize, entry: &Entry) -> Result<usize, ReadError> {
    let value = entry.value.as_deref().unwrap_or("NOVALUE");
    value.parse().map_err(|_| {
        ReadError::at(
            file,
            Some(line),
            &entry.name,
            format!("\"{value}\" is not a whole number"),
        )
    })
}

/// The value of `entry` as a finite number.
fn finite_number(file: &Path, line: usize, entry: &Entry) -> Result<f64, ReadError> {
    let value = entry.value.as_deref().unwrap_or("NOVALUE");
    (value.parse::<f64>().ok())
        .filter(|x| x.is_finite())
        .ok_or_else(|| {
            ReadError::at(
                file,
                Some(line),
                &entry.name,
                format!("\"{value}\" is not a finite number"),
            )
        })
}

/// A channel file: its header up to the first line that is not
/// `Name:value`, then its samples.
fn read_channel(text: &str, file: &Path, listed: &Listed) -> Result<Channel, ReadError> {
    let lines: Vec<&str> = text.lines().collect();
    let (numbered, data_start) = header_lines(&lines);
    let fields = Fields {
        file,
        lines: &numbered,
    };
    let (code_line, code_entry) = fields.required("Channel code")?;
    let code = code_of(file, code_line, code_entry, listed)?;
    fields.implicit_time_base()?;
    let (dt_line, dt_entry) = fields.required("Sampling interval")?;
    let dt = finite_number(file, dt_line, dt_entry)?;
    if dt <= 0.0 {
        let why = format!("{dt} is not a positive interval");
        return Err(ReadError::at(file, Some(dt_line), &dt_entry.name, why));
    }
    let (t0_line, t0_entry) = fields.required("Time of first sample")?;
    let t0 = finite_number(file, t0_line, t0_entry)?;
    let (n_line, n_entry) = fields.required("Number of samples")?;
    let count = whole_number(file, n_line, n_entry)?;
    let values = samples(&lines, data_start, file)?;
    if values.len() != count {
        let why = format!("says {count} samples; the file holds {}", values.len());
        return Err(ReadError::at(file, Some(n_line), &n_entry.name, why));
    }
    let unit = (fields.find("Unit").and_then(|(_, e)| e.value.clone())).unwrap_or_default();
    Ok(Channel {
        code,
        header: numbered.into_iter().map(|(_, e)| e).collect(),
        unit,
        t0,
        dt,
        values,
    })
}

/// The `Name:value` lines that open a channel file, with their line
/// numbers (from 1), and the index of the first line after them.
fn header_lines(lines: &[&str]) -> (Vec<(usize, Entry)>, usize) {
    let mut numbered = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        match entry_of(line) {
            Some(entry) => numbered.push((k + 1, entry)),
            None => return (numbered, k),
        }
    }
    (numbered, lines.len())
}

/// The header lines of channel file `file`, by name.
struct Fields<'a> {
    file: &'a Path,
    lines: &'a [(usize, Entry)],
}

impl<'a> Fields<'a> {
    /// The first line named `name`, with its line number.
    fn find(&self, name: &str) -> Option<(usize, &'a Entry)> {
        (self.lines.iter())
            .find(|(_, e)| e.name == name)
            .map(|(line, e)| (*line, e))
    }

    /// [`Fields::find`], or the error that it is missing.
    fn required(&self, name: &str) -> Result<(usize, &'a Entry), ReadError> {
        (self.find(name)).ok_or_else(|| missing(self.file, name, "a channel file must give it"))
    }

    /// An error where the file says its time is an explicit channel's.
    fn implicit_time_base(&self) -> Result<(), ReadError> {
        match self.find("Reference channel") {
            Some((line, entry))
                if (entry.value.as_deref()).is_some_and(|v| v.eq_ignore_ascii_case("explicit")) =>
            {
                let why = "an explicit time channel is not read; only the implicit time base t = t0 + i·dt";
                Err(ReadError::at(self.file, Some(line), &entry.name, why))
            }
            _ => Ok(()),
        }
    }
}

/// The code of a channel file, which must be the one its `.chn` lists.
fn code_of(
    file: &Path,
    line: usize,
    entry: &Entry,
    listed: &Listed,
) -> Result<ChannelCode, ReadError> {
    let at = |problem: String| ReadError::at(file, Some(line), &entry.name, problem);
    let text = entry.value.as_deref().unwrap_or("NOVALUE");
    let code = ChannelCode::parse(text).map_err(|e| at(e.to_string()))?;
    if code != listed.code {
        return Err(at(format!(
            "{code} differs from {} of the .chn (line {})",
            listed.code, listed.line
        )));
    }
    Ok(code)
}

/// The samples from line `start` on: one number a line, `NOVALUE` (NaN)
/// for none; blank lines skipped.
fn samples(lines: &[&str], start: usize, file: &Path) -> Result<Vec<f64>, ReadError> {
    let mut values = Vec::with_capacity(lines.len().saturating_sub(start));
    for (k, line) in lines.iter().enumerate().skip(start) {
        let text = line.trim();
        if text.is_empty() {
            continue;
        }
        if text.eq_ignore_ascii_case(crate::text::NOVALUE) {
            values.push(f64::NAN);
            continue;
        }
        let value = text.parse::<f64>().map_err(|_| {
            let field = format!("sample {}", values.len() + 1);
            ReadError::at(
                file,
                Some(k + 1),
                field,
                format!("\"{text}\" is not a number"),
            )
        })?;
        values.push(value);
    }
    Ok(values)
}
