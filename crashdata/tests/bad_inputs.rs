//! Malformed ISO-MME tests: each is an error naming the file, the line and
//! the field. Every case is the pyisomme reference test (`REF001`) with one
//! thing broken.

use lagrangian_crashdata::ReadError;
use lagrangian_crashdata::isomme;
use std::path::{Path, PathBuf};

fn reference() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pyisomme/REF001")
}

/// A fresh copy of the reference test in a folder of its own.
fn copy(case: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("crashdata-bad-{case}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("Channel")).unwrap();
    for name in [
        "REF001.mme",
        "Channel/REF001.chn",
        "Channel/REF001.001",
        "Channel/REF001.002",
        "Channel/REF001.003",
    ] {
        std::fs::copy(reference().join(name), dir.join(name)).unwrap();
    }
    dir
}

/// Replaces line `line` (from 1) of `file` by `text` (`None`: removes it).
fn edit_line(file: &Path, line: usize, text: Option<&str>) {
    let old = std::fs::read_to_string(file).unwrap();
    let mut lines: Vec<&str> = old.lines().collect();
    match text {
        Some(text) => lines[line - 1] = text,
        None => {
            lines.remove(line - 1);
        }
    }
    std::fs::write(file, lines.join("\n") + "\n").unwrap();
}

/// The line (from 1) of `file` that starts with `prefix`.
fn line_of(file: &Path, prefix: &str) -> usize {
    let text = std::fs::read_to_string(file).unwrap();
    text.lines().position(|l| l.starts_with(prefix)).unwrap() + 1
}

fn error(dir: &Path) -> ReadError {
    let e = isomme::read(dir).unwrap_err();
    println!("{e}");
    let _ = std::fs::remove_dir_all(dir);
    e
}

#[test]
fn a_missing_sampling_interval_names_the_channel_file_and_the_field() {
    let dir = copy("interval");
    let file = dir.join("Channel/REF001.002");
    edit_line(&file, line_of(&file, "Sampling interval"), None);
    let e = error(&dir);
    assert_eq!(e.file, file);
    assert_eq!(e.field.as_deref(), Some("Sampling interval"));
    assert_eq!(e.line, None);
    assert!(e.problem.contains("missing"), "{e}");
}

#[test]
fn a_missing_channel_name_in_the_chn_names_its_key() {
    let dir = copy("chn");
    let file = dir.join("Channel/REF001.chn");
    edit_line(&file, line_of(&file, "Name of channel 002"), None);
    let e = error(&dir);
    assert_eq!(e.file, file);
    assert_eq!(e.field.as_deref(), Some("Name of channel 002"));
}

#[test]
fn a_wrong_sample_count_names_the_line_of_number_of_samples() {
    let dir = copy("count");
    let file = dir.join("Channel/REF001.003");
    let line = line_of(&file, "Number of samples");
    edit_line(&file, line, Some("Number of samples           :1201"));
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(line)));
    assert_eq!(e.field.as_deref(), Some("Number of samples"));
    assert!(
        e.problem.contains("says 1201 samples; the file holds 1200"),
        "{e}"
    );
}

#[test]
fn a_bad_code_names_the_line_and_the_code_field() {
    let dir = copy("code");
    let file = dir.join("Channel/REF001.chn");
    let line = line_of(&file, "Name of channel 001");
    edit_line(
        &file,
        line,
        Some("Name of channel 001         :10VEHCCG0000QQXP / Vehicle"),
    );
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(line)));
    assert_eq!(e.field.as_deref(), Some("Name of channel 001"));
    assert!(
        e.problem
            .contains("physical dimension (position 13) is \"QQ\""),
        "{e}"
    );
    // In the channel file itself.
    let dir = copy("code-channel");
    let file = dir.join("Channel/REF001.001");
    let line = line_of(&file, "Channel code");
    edit_line(
        &file,
        line,
        Some("Channel code                :10VEHCCG0000ACX"),
    );
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(line)));
    assert_eq!(e.field.as_deref(), Some("Channel code"));
    assert!(e.problem.contains("15 characters"), "{e}");
}

#[test]
fn an_unparsable_sample_names_its_line_and_number() {
    let dir = copy("sample");
    let file = dir.join("Channel/REF001.002");
    let first = line_of(&file, "Time of minimum value") + 1;
    edit_line(&file, first + 4, Some("1,25"));
    let e = error(&dir);
    assert_eq!(
        (e.file.as_path(), e.line),
        (file.as_path(), Some(first + 4))
    );
    assert_eq!(e.field.as_deref(), Some("sample 5"));
    assert!(e.problem.contains("\"1,25\" is not a number"), "{e}");
}

#[test]
fn an_unparsable_header_number_names_its_line() {
    let dir = copy("t0");
    let file = dir.join("Channel/REF001.001");
    let line = line_of(&file, "Time of first sample");
    edit_line(
        &file,
        line,
        Some("Time of first sample        :minus ten ms"),
    );
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(line)));
    assert_eq!(e.field.as_deref(), Some("Time of first sample"));
}

#[test]
fn a_line_of_the_mme_that_is_not_name_value_names_its_line() {
    let dir = copy("mme");
    let file = dir.join("REF001.mme");
    edit_line(&file, 3, Some("just some words"));
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(3)));
}

#[test]
fn a_missing_channel_file_names_the_file_and_its_chn_line() {
    let dir = copy("file");
    std::fs::remove_file(dir.join("Channel/REF001.003")).unwrap();
    let e = error(&dir);
    assert_eq!(e.file, dir.join("Channel/REF001.003"));
    assert!(e.problem.contains("Name of channel 003"), "{e}");
}

#[test]
fn a_zip_without_an_mme_names_the_zip() {
    use std::io::Write;
    let path = std::env::temp_dir().join(format!("crashdata-bad-{}.zip", std::process::id()));
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&path).unwrap());
    let options = zip::write::SimpleFileOptions::default();
    zip.start_file("Channel/REF001.chn", options).unwrap();
    zip.write_all(b"Number of channels          :0\n").unwrap();
    zip.finish().unwrap();
    let e = isomme::read(&path).unwrap_err();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(
        (e.file.as_path(), e.line, e.field.as_deref()),
        (path.as_path(), None, None)
    );
    assert!(e.problem.contains("no .mme file"), "{e}");
    // Not a zip at all.
    let path = std::env::temp_dir().join(format!("crashdata-bad-text-{}.zip", std::process::id()));
    std::fs::write(&path, "not a zip").unwrap();
    let e = isomme::read(&path).unwrap_err();
    std::fs::remove_file(&path).unwrap();
    assert_eq!(e.file, path);
    assert!(e.problem.contains("not a readable zip"), "{e}");
}

#[test]
fn a_folder_with_two_tests_asks_which() {
    let dir = copy("two");
    std::fs::copy(dir.join("REF001.mme"), dir.join("REF002.mme")).unwrap();
    let e = error(&dir);
    assert_eq!(e.file, dir);
    assert!(e.problem.contains("2 .mme files"), "{e}");
}

#[test]
fn an_explicit_time_channel_is_refused_at_its_line() {
    let dir = copy("explicit");
    let file = dir.join("Channel/REF001.003");
    let line = line_of(&file, "Reference channel");
    edit_line(&file, line, Some("Reference channel           :explicit"));
    let e = error(&dir);
    assert_eq!((e.file.as_path(), e.line), (file.as_path(), Some(line)));
    assert_eq!(e.field.as_deref(), Some("Reference channel"));
}
