//! Time histories from CSV files with units in the header, e.g.
//!
//! ```text
//! t [ms], acceleration [g], velocity [km/h], crush [mm]
//! 0.0,    0.0,              56.0,            0.0
//! ```
//!
//! Every column the tool reads carries its unit in brackets; values are
//! converted to SI. Columns with other names are ignored.

use crate::files::Files;
use crate::table::{Table, TableError};
use std::path::Path;

/// What a column measures, with the sign conventions of [`super`]:
/// forward positive, crush positive in compression.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// Vehicle acceleration [m/s²] (negative while decelerating).
    Acceleration,
    /// Vehicle velocity [m/s].
    Velocity,
    /// Crush \[m\].
    Crush,
}

impl Quantity {
    /// The quantity in words, as messages name it (`acceleration`).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Acceleration => "acceleration",
            Quantity::Velocity => "velocity",
            Quantity::Crush => "crush",
        }
    }

    /// The SI unit its values are converted to, in ASCII (`m/s^2`).
    pub fn si_unit(self) -> &'static str {
        match self {
            Quantity::Acceleration => "m/s^2",
            Quantity::Velocity => "m/s",
            Quantity::Crush => "m",
        }
    }
}

/// One channel, in SI units.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// What it measures; a file has at most one channel of each.
    pub quantity: Quantity,
    /// The header cell it came from.
    pub header: String,
    /// One value per row of the file, in [`Quantity::si_unit`] and the
    /// sign conventions above (a `decel` column is negated).
    pub values: Vec<f64>,
}

/// The channels of a file, on its time column.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeHistories {
    /// Sample times \[s\], strictly increasing, at least 3.
    pub t: Vec<f64>,
    /// At least one, each as long as `t`, sorted by quantity
    /// (acceleration, velocity, crush).
    pub channels: Vec<Channel>,
}

impl TimeHistories {
    /// The channel of `quantity`, if the file has one.
    pub fn channel(&self, quantity: Quantity) -> Option<&Channel> {
        self.channels.iter().find(|c| c.quantity == quantity)
    }
}

/// Why a file gives no time histories.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChannelError {
    /// The file cannot be read as a table of numbers, is shorter than 3
    /// rows, or its time does not increase.
    #[error("{0}")]
    Table(TableError),
    /// A column this tool reads has no `[unit]`, or one it does not know.
    #[error(
        "{file}: column `{header}` needs a unit in brackets, one of {known} (e.g. `{} [{}]`)",
        name_of(.header),
        first_unit(.known)
    )]
    Unit {
        /// The file, as displayed in messages.
        file: String,
        /// The whole header cell, e.g. `velocity [kph]`.
        header: String,
        /// The units accepted for that quantity, comma separated, the
        /// first one used as the example.
        known: &'static str,
    },
    /// No time column, or none of acceleration, velocity, crush.
    #[error("{file}: no {what} column (columns: {})", .headers.join(", "))]
    Missing {
        /// The file, as displayed in messages.
        file: String,
        /// What is missing, in words with the expected header.
        what: String,
        /// The header cells the file has.
        headers: Vec<String>,
    },
    /// Two columns measure the same quantity.
    #[error("{file}: two columns hold the {quantity}; keep one")]
    Duplicate {
        /// The file, as displayed in messages.
        file: String,
        /// `time` or the [`Quantity::name`] that is there twice.
        quantity: &'static str,
    },
}

/// The column name of a header cell, without its `[unit]`.
fn name_of(header: &str) -> &str {
    header.split('[').next().unwrap_or(header).trim()
}

/// The first of a comma-separated list of units, for an example.
fn first_unit(known: &str) -> &str {
    known.split(", ").next().unwrap_or("")
}

/// The quantity a column name stands for, `None` for the time column.
fn quantity_of(name: &str) -> Option<Option<(Quantity, f64)>> {
    match name.to_ascii_lowercase().as_str() {
        "t" | "time" => Some(None),
        "a" | "acceleration" | "accel" | "ax" => Some(Some((Quantity::Acceleration, 1.0))),
        "deceleration" | "decel" => Some(Some((Quantity::Acceleration, -1.0))),
        "v" | "velocity" | "vx" => Some(Some((Quantity::Velocity, 1.0))),
        "crush" | "displacement" | "deformation" | "x" => Some(Some((Quantity::Crush, 1.0))),
        _ => None,
    }
}

/// SI factor of `unit` for a column of `quantity` (`None`: time), and the
/// units accepted.
fn unit_factor(quantity: Option<Quantity>, unit: &str) -> (Option<f64>, &'static str) {
    let unit = unit.trim();
    match quantity {
        None => (
            match unit {
                "s" => Some(1.0),
                "ms" => Some(1e-3),
                _ => None,
            },
            "s, ms",
        ),
        Some(Quantity::Acceleration) => (
            match unit {
                "m/s^2" | "m/s²" | "m/s2" => Some(1.0),
                "g" => Some(super::STANDARD_GRAVITY),
                "mm/ms^2" | "km/s^2" => Some(1000.0),
                _ => None,
            },
            "g, m/s^2, mm/ms^2",
        ),
        Some(Quantity::Velocity) => (
            match unit {
                "m/s" | "mm/ms" => Some(1.0),
                "km/h" => Some(1.0 / 3.6),
                "mph" => Some(0.44704),
                _ => None,
            },
            "m/s, km/h, mm/ms, mph",
        ),
        Some(Quantity::Crush) => (
            match unit {
                "m" => Some(1.0),
                "mm" => Some(1e-3),
                _ => None,
            },
            "m, mm",
        ),
    }
}

/// Reads the time column and the acceleration, velocity and crush columns
/// (at least one) of the CSV file `path` of `files`, in SI units.
pub fn read_time_histories(files: &dyn Files, path: &Path) -> Result<TimeHistories, ChannelError> {
    let table = files.table(path).map_err(ChannelError::Table)?;
    from_table(&table)
}

/// The time histories of a table already read (see
/// [`read_time_histories`]): the columns named as a quantity, with their
/// units, converted to SI; other columns are ignored.
pub fn from_table(table: &Table) -> Result<TimeHistories, ChannelError> {
    let file = table.file().display().to_string();
    let mut time: Option<Vec<f64>> = None;
    let mut channels: Vec<Channel> = Vec::new();
    for (k, header) in table.headers().iter().enumerate() {
        let (name, unit) = match header.split_once('[') {
            Some((n, u)) => (n.trim(), Some(u.trim_end().trim_end_matches(']'))),
            None => (header.trim(), None),
        };
        let Some(kind) = quantity_of(name) else {
            continue;
        };
        let quantity = kind.map(|(q, _)| q);
        let (factor, known) = unit_factor(quantity, unit.unwrap_or(""));
        let Some(factor) = factor else {
            return Err(ChannelError::Unit {
                file,
                header: header.clone(),
                known,
            });
        };
        let values: Vec<f64> = table.column(k).iter().map(|x| x * factor).collect();
        match kind {
            None if time.is_some() => {
                return Err(ChannelError::Duplicate {
                    file,
                    quantity: "time",
                });
            }
            None => time = Some(values),
            Some((quantity, sign)) => {
                if channels.iter().any(|c| c.quantity == quantity) {
                    return Err(ChannelError::Duplicate {
                        file,
                        quantity: quantity.name(),
                    });
                }
                channels.push(Channel {
                    quantity,
                    header: header.clone(),
                    values: values.into_iter().map(|x| sign * x).collect(),
                });
            }
        }
    }
    let headers = table.headers().to_vec();
    let Some(t) = time else {
        return Err(ChannelError::Missing {
            file,
            what: "time (`t [s]` or `t [ms]`)".into(),
            headers,
        });
    };
    if channels.is_empty() {
        return Err(ChannelError::Missing {
            file,
            what: "acceleration, deceleration, velocity or crush".into(),
            headers,
        });
    }
    if t.len() < 3 {
        return Err(ChannelError::Table(TableError::TooShort {
            file: table.file().to_path_buf(),
            rows: t.len(),
        }));
    }
    if let Some(i) = (1..t.len()).find(|&i| t[i] <= t[i - 1]) {
        return Err(ChannelError::Table(TableError::NotIncreasing {
            file: table.file().to_path_buf(),
            line: table.line(i),
            time: t[i],
            previous: t[i - 1],
        }));
    }
    channels.sort_by_key(|c| c.quantity);
    Ok(TimeHistories { t, channels })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<TimeHistories, ChannelError> {
        from_table(&Table::parse(Path::new("pulse.csv"), text).unwrap())
    }

    #[test]
    fn units_are_converted_to_si() {
        let h = parse("t [ms],decel [g],velocity [km/h],crush [mm],force [kN]\n0,1,36,0,5\n1,2,18,10,6\n2,3,0,20,7\n")
            .unwrap();
        assert_eq!(h.t, vec![0.0, 1e-3, 2e-3]);
        let a = &h.channel(Quantity::Acceleration).unwrap().values;
        assert!((a[1] + 2.0 * 9.80665).abs() < 1e-12);
        let v = &h.channel(Quantity::Velocity).unwrap().values;
        assert!((v[0] - 10.0).abs() < 1e-12);
        let c = &h.channel(Quantity::Crush).unwrap().values;
        assert!((c[2] - 0.02).abs() < 1e-15);
        assert_eq!(h.channels.len(), 3, "the force column is not read");
    }

    #[test]
    fn missing_units_columns_and_order_are_reported_with_their_place() {
        let e = parse("t [s],acceleration\n0,1\n1,2\n2,3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "pulse.csv: column `acceleration` needs a unit in brackets, one of g, m/s^2, mm/ms^2 (e.g. `acceleration [g]`)"
        );
        let e = parse("time [s],force [N]\n0,1\n1,2\n2,3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "pulse.csv: no acceleration, deceleration, velocity or crush column (columns: time [s], force [N])"
        );
        let e = parse("t [s],a [g]\n0,1\n0.2,2\n0.1,3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "pulse.csv:4: time 0.1 does not increase (previous row has 0.2); sort the rows by time"
        );
        let e = parse("t [s],a [g],accel [g]\n0,1,1\n1,2,2\n2,3,3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "pulse.csv: two columns hold the acceleration; keep one"
        );
        let e = parse("t [s],a [furlongs]\n0,1\n1,2\n2,3\n").unwrap_err();
        assert!(
            e.to_string().contains("column `a [furlongs]` needs a unit"),
            "{e}"
        );
    }
}
