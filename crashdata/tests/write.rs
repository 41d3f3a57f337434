//! Writing a test: the files and their format, the values read back, and
//! nothing half-written.

use lagrangian_crashdata::isomme::{self, Channel, Test};
use lagrangian_crashdata::text::Header;
use lagrangian_crashdata::{ChannelCode, WriteError};
use std::path::{Path, PathBuf};

fn scratch(case: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("crashdata-write-{case}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn reference() -> Test {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/pyisomme/REF001");
    isomme::read(&dir).unwrap()
}

/// Every entry of `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_test_written_reads_back_with_the_same_samples_and_lines() {
    let test = reference();
    let root = scratch("roundtrip");
    let dir = root.join("copy");
    isomme::write(&test, &dir).unwrap();
    assert_eq!(listing(&dir), ["Channel", "REF001.mme"]);
    let channel_files = listing(&dir.join("Channel"));
    assert_eq!(
        channel_files,
        ["REF001.001", "REF001.002", "REF001.003", "REF001.chn"]
    );
    let back = isomme::read(&dir).unwrap();
    assert_eq!(back.info, test.info);
    assert_eq!(back.channel_info, test.channel_info);
    for (a, b) in back.channels.iter().zip(&test.channels) {
        assert_eq!((a.code, &a.unit, a.t0, a.dt), (b.code, &b.unit, b.t0, b.dt));
        assert_eq!(a.values.len(), b.values.len());
        for (x, y) in a.values.iter().zip(&b.values) {
            assert!(x == y || (x.is_nan() && y.is_nan()), "{}: {x} {y}", a.code);
        }
        // Every line is there, in its place; only the extremes are this
        // writer's (pyisomme writes `nan` for a channel with a NaN).
        let names = |h: &Header| {
            h.entries()
                .iter()
                .map(|e| e.name.clone())
                .collect::<Vec<_>>()
        };
        assert_eq!(names(&a.header), names(&b.header));
    }
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn the_files_are_iso_8859_1_names_padded_to_28() {
    let test = reference();
    let root = scratch("latin1");
    isomme::write(&test, &root.join("t")).unwrap();
    let mme = std::fs::read(root.join("t/REF001.mme")).unwrap();
    let line = b"Laboratory name             :Pr\xFCfstand S\xFCd\n";
    assert!(mme.windows(line.len()).any(|w| w == line));
    let chn = std::fs::read_to_string(root.join("t/Channel/REF001.chn")).unwrap();
    assert!(chn.contains("Number of channels          :3\n"), "{chn}");
    assert!(
        chn.contains(
            "Name of channel 002         :11HEAD0000H3ACXA / Driver head acceleration X\n"
        )
    );
    let head = std::fs::read_to_string(root.join("t/Channel/REF001.002")).unwrap();
    for line in [
        "Channel code                :11HEAD0000H3ACXA\n",
        "Unit                        :g\n",
        "Reference channel           :implicit\n",
        "Time of first sample        :-0.02\n",
        "Number of samples           :1700\n",
    ] {
        assert!(head.contains(line), "{line}");
    }
    std::fs::remove_dir_all(&root).unwrap();
}

/// A channel of `values` at 1 kHz from 0, with an empty header.
fn channel(code: &str, values: Vec<f64>) -> Channel {
    Channel {
        code: ChannelCode::parse(code).unwrap(),
        header: Header::new(),
        unit: "N".into(),
        t0: 0.0,
        dt: 1e-3,
        values,
    }
}

#[test]
fn the_extremes_are_the_first_largest_and_smallest_samples() {
    let test = Test {
        name: "X".into(),
        info: Header::new(),
        channel_info: Header::new(),
        channels: vec![channel(
            "B0FBAR000000FOXP",
            vec![0.0, 3.0, f64::NAN, 3.0, -2.0, -2.0],
        )],
    };
    let root = scratch("extremes");
    isomme::write(&test, &root.join("t")).unwrap();
    let text = std::fs::read_to_string(root.join("t/Channel/X.001")).unwrap();
    for line in [
        "First global maximum value  :3\n",
        "Time of maximum value       :0.001\n",
        "First global minimum value  :-2\n",
        "Time of minimum value       :0.004\n",
        "\nNOVALUE\n",
    ] {
        assert!(text.contains(line), "{line:?} in\n{text}");
    }
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn a_failed_write_leaves_the_old_test_and_no_temporary() {
    let root = scratch("atomic");
    let dir = root.join("t");
    isomme::write(&reference(), &dir).unwrap();
    let before = std::fs::read(dir.join("Channel/REF001.001")).unwrap();
    let mut bad = reference();
    bad.channels[2].dt = 0.0;
    let e = isomme::write(&bad, &dir).unwrap_err();
    assert!(matches!(e, WriteError::Channel { index: 3, .. }), "{e}");
    assert_eq!(
        std::fs::read(dir.join("Channel/REF001.001")).unwrap(),
        before
    );
    assert_eq!(listing(&root), ["t"]);
    // A good write replaces it whole: a file of the old test is gone.
    let mut smaller = reference();
    smaller.channels.truncate(1);
    isomme::write(&smaller, &dir).unwrap();
    assert_eq!(listing(&dir.join("Channel")), ["REF001.001", "REF001.chn"]);
    assert_eq!(listing(&root), ["t"]);
    // A name that is a path is refused before anything is written.
    let mut bad = smaller;
    bad.name = "../escape".into();
    assert!(matches!(
        isomme::write(&bad, &root.join("u")),
        Err(WriteError::Name(_))
    ));
    assert_eq!(listing(&root), ["t"]);
    std::fs::remove_dir_all(&root).unwrap();
}
