//! NHTSA's EV5 ASCII X-Y tests: the card file `v<test>.EV5` and a channel
//! file `v<test>.NNN` per instrumentation card.
//!
//! The card file, as NHTSA's downloads hold it (e.g. test 10146, kept in
//! github.com/joe-cormier/pycrash; field names as p4trucc0/nhtsa2mat
//! documents them — the format only, no code of either):
//!
//! ```text
//! ----- EV5 -----
//! ----- TEST -----
//! V5|NCAP - 2018 TOYOTA CAMRY …|…|03/OCT/2017|…|57.09|0|0|0|634|…
//! ----- VEHICLE -----            (one card per vehicle)
//! ----- BARRIER -----            (optional)
//! ----- OCCUPANT -----           (optional, one card per occupant)
//! ----- RESTRAINT -----          (optional)
//! ----- INSTRUMENTATION -----    (one card per channel)
//! 1|1|AC|01|HDCG|XL|SEC|G'S|2800|MFG: …|11/AUG/2017|1200|4|57.09|-500|2999|100|AM|P|DRIVER HEAD X
//! ----- END -----
//! ```
//!
//! A card is one line of `|`-separated fields, named by their place
//! ([`TEST_FIELDS`], [`INSTRUMENTATION_FIELDS`], …); a field beyond the
//! names is `FIELD<n>` (from 1); lines starting with `#` are comments.
//! What an instrumentation card's fields mean, from the same test: `CURNO`
//! the channel number, `SENTYP` the sensor (`AC` accelerometer, `LC` load
//! cell, `DS` displacement, `AV` angular rate), `SENLOC` the occupant
//! position (`01` driver, `NA` the vehicle), `SENATT` where it is attached,
//! `AXIS` (`XL` local, `XG` global), `XUNITS` `SEC`, `YUNITS` (`G'S`,
//! `NWT` newtons, `NWM` newton-metres, `MM`, `DPS` degrees a second),
//! `INIVEL` the initial velocity \[km/h\], `NFP` and `NLP` the first and
//! last sample numbers, `DELT` the sampling interval in microseconds (its
//! channel files start at `NFP·DELT`: −500 · 100 µs = −0.05 s), `DASTAT`
//! the data status (`AM` as measured, `NO` not installed: no file),
//! `CHSTAT` primary or redundant (`P`, `R`), `INSCOM` the description.
//!
//! A channel file holds one sample a line: the time \[s\] and the value,
//! separated by a tab (any whitespace is read), `NLP − NFP + 1` lines.

use crate::error::ReadError;
use std::path::{Path, PathBuf};

/// The fields of a `TEST` card.
pub const TEST_FIELDS: &[&str] = &[
    "VERNO", "TITLE", "TSTOBJ", "TSTDAT", "TSTPRF", "CONNO", "TSTREF", "TSTTYP", "TSTCNF",
    "TKSURF", "TKCOND", "TEMP", "RECTYP", "LINK", "CLSSPD", "IMPANG", "OFFSET", "IMPPNT", "TOTCRV",
    "TSTCOM",
];

/// The fields of a `VEHICLE` card.
pub const VEHICLE_FIELDS: &[&str] = &[
    "VEHNO", "MAKE", "MODEL", "YEAR", "NHTSANO", "BODY", "VIN", "ENGINE", "ENGDSP", "TRANSM",
    "VEHTWT", "CURBWT", "WHLBAS", "VEHLEN", "VEHWID", "VEHCG", "STRSEP", "COLMEC", "MODIND",
    "MODDSC", "BX1", "BX2", "BX3", "BX4", "BX5", "BX6", "BX7", "BX8", "BX9", "BX10", "BX11",
    "BX12", "BX13", "BX14", "BX15", "BX16", "BX17", "BX18", "BX19", "BX20", "BX21", "VEHSPD",
    "CRBANG", "PDOF", "BMPENG", "SILENG", "APLENG", "DPD1", "DPD2", "DPD3", "DPD4", "DPD5", "DPD6",
    "VDI", "LENCNT", "DAMDST", "CRHDST", "AX1", "AX2", "AX3", "AX4", "AX5", "AX6", "AX7", "AX8",
    "AX9", "AX10", "AX11", "AX12", "AX13", "AX14", "AX15", "AX16", "AX17", "AX18", "AX19", "AX20",
    "AX21", "CARANG", "VEHOR", "VEHCOM",
];

/// The fields of a `BARRIER` card.
pub const BARRIER_FIELDS: &[&str] = &["BARRIG", "BARSHP", "BARANG", "BARDIA", "BARCOM"];

/// The fields of an `OCCUPANT` card.
pub const OCCUPANT_FIELDS: &[&str] = &[
    "VEHNO", "OCCLOC", "OCCTYP", "OCCAGE", "OCCSEX", "OCCHT", "OCCWT", "MTHCAL", "DUMMSIZ",
    "DUMMAN", "DUMMOD", "DUMDSC", "HH", "HW", "HR", "HS", "CD", "CS", "AD", "HD", "KD", "HB", "NB",
    "CB", "KB", "SEPOSN", "CNTRH1", "CNTRH2", "CNTRC1", "CNTRC2", "CNTRL1", "CNTRL2", "HIC", "T1",
    "T2", "CLIP3M", "LFEM", "RFEM", "CSI", "LBELT", "SBELT", "TTI", "PELVG", "OCCCOM",
];

/// The fields of a `RESTRAINT` card.
pub const RESTRAINT_FIELDS: &[&str] = &[
    "VEHNO", "OCCLOC", "RSTNO", "RSTTYP", "RSTMNT", "DEPLOY", "RSTCOM",
];

/// The fields of an `INSTRUMENTATION` card.
pub const INSTRUMENTATION_FIELDS: &[&str] = &[
    "VEHNO", "CURNO", "SENTYP", "SENLOC", "SENATT", "AXIS", "XUNITS", "YUNITS", "PREFIL", "INSMAN",
    "CALDAT", "INSRAT", "CHLMAX", "INIVEL", "NFP", "NLP", "DELT", "DASTAT", "CHSTAT", "INSCOM",
];

/// A test read from an EV5 card file and its channel files.
#[derive(Clone, Debug, PartialEq)]
pub struct Ev5Test {
    /// The card file's stem (`v10146`).
    pub name: String,
    /// The card file's sections in order (`TEST`, `VEHICLE`, …,
    /// `INSTRUMENTATION`), every card of each.
    pub sections: Vec<Section>,
    /// A channel per instrumentation card, in order.
    pub channels: Vec<Ev5Channel>,
}

impl Ev5Test {
    /// The section named `name` (`VEHICLE`).
    pub fn section(&self, name: &str) -> Option<&Section> {
        self.sections.iter().find(|s| s.name == name)
    }

    /// The `TEST` card.
    pub fn test_card(&self) -> Option<&Card> {
        self.section("TEST").and_then(|s| s.cards.first())
    }

    /// The channel numbered `number` (`CURNO`).
    pub fn channel(&self, number: u32) -> Option<&Ev5Channel> {
        self.channels.iter().find(|c| c.number == number)
    }
}

/// A section of the card file: `----- NAME -----` and its cards.
#[derive(Clone, Debug, PartialEq)]
pub struct Section {
    /// `TEST`, `VEHICLE`, `BARRIER`, `OCCUPANT`, `RESTRAINT`,
    /// `INSTRUMENTATION` (or another name the file gives).
    pub name: String,
    /// Its cards, in order.
    pub cards: Vec<Card>,
}

/// One card: a line of `|`-separated fields, each with its name.
#[derive(Clone, Debug, PartialEq)]
pub struct Card {
    /// Its line in the card file, from 1.
    pub line: usize,
    /// `(name, value)` per field, in order; values trimmed.
    pub fields: Vec<(String, String)>,
}

impl Card {
    /// The value of field `name`; `None` where it is absent or empty.
    pub fn get(&self, name: &str) -> Option<&str> {
        (self.fields.iter())
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
            .filter(|v| !v.is_empty())
    }
}

/// One channel: its instrumentation card and its samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Ev5Channel {
    /// `CURNO`: the channel number, its file's extension.
    pub number: u32,
    /// `INSCOM`: what it is ("LEFT REAR SEAT CROSSMEMBER X").
    pub description: String,
    /// `YUNITS`: the unit of its values as NHTSA writes it (`G'S`, `NWT`).
    pub y_units: String,
    /// `DELT` in seconds: the sampling interval.
    pub dt: f64,
    /// `NFP`: the number of the first sample (`t = NFP·DELT`).
    pub first_point: i64,
    /// `NLP`: the number of the last sample.
    pub last_point: i64,
    /// The whole card (every field, the ones above included).
    pub card: Card,
    /// The samples; `None` where its file is missing (a channel whose
    /// `DASTAT` is `NO`: not installed).
    pub data: Option<Samples>,
}

impl Ev5Channel {
    /// The unit of its values as ISO-MME writes it (`G'S` → `g`, `NWT` →
    /// `N`, `NWM` → `Nm`, `MM` → `mm`, `DPS` → `deg/s`, …); `None` for a
    /// unit not known here.
    pub fn unit(&self) -> Option<&'static str> {
        Some(match self.y_units.to_ascii_uppercase().as_str() {
            "G'S" | "G" | "GS" => "g",
            "NWT" | "N" => "N",
            "NWM" | "NM" => "Nm",
            "MM" => "mm",
            "CM" => "cm",
            "M" => "m",
            "DPS" | "DEG/SEC" => "deg/s",
            "DEG" => "deg",
            "RPS" | "RAD/SEC" => "rad/s",
            "KPH" | "KMH" => "km/h",
            "MPS" => "m/s",
            "KPA" => "kPa",
            "SEC" => "s",
            _ => return None,
        })
    }
}

/// A channel's samples.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples {
    /// Time of each sample \[s\].
    pub times: Vec<f64>,
    /// The values, in the channel's unit.
    pub values: Vec<f64>,
}

/// Reads the card file at `path` and the channel files beside it.
pub fn read(path: &Path) -> Result<Ev5Test, ReadError> {
    let bytes =
        std::fs::read(path).map_err(|e| ReadError::file(path, format!("cannot read: {e}")))?;
    let sections = sections(&crate::text::decode(&bytes), path)?;
    let name = (path.file_stem()).map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let folder = path.parent().unwrap_or(Path::new("."));
    let listing = folder_listing(folder)?;
    let cards = sections.iter().filter(|s| s.name == "INSTRUMENTATION");
    let mut channels = Vec::new();
    for card in cards.flat_map(|s| &s.cards) {
        channels.push(channel(card, path, &name, &listing)?);
    }
    Ok(Ev5Test {
        name,
        sections,
        channels,
    })
}

/// The sections of a card file's `text`, up to `----- END -----`.
fn sections(text: &str, file: &Path) -> Result<Vec<Section>, ReadError> {
    let mut sections: Vec<Section> = Vec::new();
    let mut ended = false;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if let Some(name) = section_name(line) {
            match name.as_str() {
                "EV5" => {}
                "END" => {
                    ended = true;
                    break;
                }
                _ => sections.push(Section {
                    name,
                    cards: Vec::new(),
                }),
            }
            continue;
        }
        let Some(section) = sections.last_mut() else {
            let why = "a card before any section (----- TEST -----)";
            return Err(ReadError::at(file, Some(k + 1), "card", why));
        };
        section
            .cards
            .push(card(line, k + 1, field_names(&section.name)));
    }
    if !ended {
        return Err(ReadError::file(
            file,
            "no ----- END ----- line: the card file is cut short",
        ));
    }
    Ok(sections)
}

/// `NAME` of a line `----- NAME -----`.
fn section_name(line: &str) -> Option<String> {
    let inner = line.strip_prefix("-----")?.strip_suffix("-----")?;
    let name = inner.trim_matches(|c: char| c == '-' || c.is_whitespace());
    (!name.is_empty()).then(|| name.to_string())
}

/// The names of the fields of a card of section `name`.
fn field_names(name: &str) -> &'static [&'static str] {
    match name {
        "TEST" => TEST_FIELDS,
        "VEHICLE" => VEHICLE_FIELDS,
        "BARRIER" => BARRIER_FIELDS,
        "OCCUPANT" => OCCUPANT_FIELDS,
        "RESTRAINT" => RESTRAINT_FIELDS,
        "INSTRUMENTATION" => INSTRUMENTATION_FIELDS,
        _ => &[],
    }
}

/// The card of `line` (at line `number`), its fields named by `names`.
fn card(line: &str, number: usize, names: &[&str]) -> Card {
    let fields = (line.split('|').enumerate())
        .map(|(k, value)| {
            let name = names
                .get(k)
                .map_or(format!("FIELD{}", k + 1), |n| n.to_string());
            (name, value.trim().to_string())
        })
        .collect();
    Card {
        line: number,
        fields,
    }
}

/// The files of `folder`, by name.
fn folder_listing(folder: &Path) -> Result<Vec<(String, PathBuf)>, ReadError> {
    let listing = std::fs::read_dir(folder)
        .map_err(|e| ReadError::file(folder, format!("cannot list: {e}")))?;
    let mut files = Vec::new();
    for item in listing {
        let item = item.map_err(|e| ReadError::file(folder, format!("cannot list: {e}")))?;
        files.push((item.file_name().to_string_lossy().into_owned(), item.path()));
    }
    Ok(files)
}

/// The channel of instrumentation `card` of the card file `file`.
fn channel(
    card: &Card,
    file: &Path,
    test: &str,
    listing: &[(String, PathBuf)],
) -> Result<Ev5Channel, ReadError> {
    let field = |name: &str| {
        card.get(name).ok_or_else(|| {
            ReadError::at(
                file,
                Some(card.line),
                name,
                "missing (an instrumentation card gives it)",
            )
        })
    };
    let number = parsed::<u32>(file, card, "CURNO", field("CURNO")?)?;
    let delt = parsed::<f64>(file, card, "DELT", field("DELT")?)?;
    if !(delt.is_finite() && delt > 0.0) {
        return Err(ReadError::at(
            file,
            Some(card.line),
            "DELT",
            format!("{delt} µs is not a positive interval"),
        ));
    }
    let first_point = parsed::<i64>(file, card, "NFP", field("NFP")?)?;
    let last_point = parsed::<i64>(file, card, "NLP", field("NLP")?)?;
    let wanted = format!("{test}.{number:03}").to_lowercase();
    let data_file = listing.iter().find(|(n, _)| n.to_lowercase() == wanted);
    let data = match data_file {
        Some((_, path)) => {
            let samples = samples(path)?;
            check_count(&samples, (first_point, last_point), path, card, file)?;
            Some(samples)
        }
        None => None,
    };
    Ok(Ev5Channel {
        number,
        description: card.get("INSCOM").unwrap_or_default().to_string(),
        y_units: card.get("YUNITS").unwrap_or_default().to_string(),
        dt: delt * 1e-6,
        first_point,
        last_point,
        card: card.clone(),
        data,
    })
}

/// The value of field `name` of `card` as a `T`.
fn parsed<T: std::str::FromStr>(
    file: &Path,
    card: &Card,
    name: &str,
    text: &str,
) -> Result<T, ReadError> {
    text.parse().map_err(|_| {
        ReadError::at(
            file,
            Some(card.line),
            name,
            format!("\"{text}\" is not a number of its kind"),
        )
    })
}

/// A channel file's `NLP − NFP + 1` samples.
fn check_count(
    samples: &Samples,
    (first, last): (i64, i64),
    path: &Path,
    card: &Card,
    file: &Path,
) -> Result<(), ReadError> {
    let expected = last - first + 1;
    if samples.times.len() as i64 == expected {
        return Ok(());
    }
    Err(ReadError::at(
        path,
        None,
        "NLP",
        format!(
            "holds {} samples; NFP = {first} and NLP = {last} of its card ({}:{}) say {expected}",
            samples.times.len(),
            file.display(),
            card.line
        ),
    ))
}

/// The `time value` lines of a channel file.
fn samples(path: &Path) -> Result<Samples, ReadError> {
    let bytes =
        std::fs::read(path).map_err(|e| ReadError::file(path, format!("cannot read: {e}")))?;
    let text = crate::text::decode(&bytes);
    let mut samples = Samples::default();
    for (k, line) in text.lines().enumerate() {
        let mut columns = line.split_whitespace();
        let (Some(t), Some(y)) = (columns.next(), columns.next()) else {
            if line.trim().is_empty() {
                continue;
            }
            let why = format!("\"{}\" is not a time and a value", line.trim());
            return Err(ReadError::at(path, Some(k + 1), "sample", why));
        };
        let number = |text: &str, what: &str| {
            text.parse::<f64>().map_err(|_| {
                ReadError::at(
                    path,
                    Some(k + 1),
                    what,
                    format!("\"{text}\" is not a number"),
                )
            })
        };
        samples.times.push(number(t, "time")?);
        samples.values.push(number(y, "value")?);
    }
    Ok(samples)
}
