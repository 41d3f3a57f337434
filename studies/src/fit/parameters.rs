//! The parameters a fit varies: `--fit` names resolved against the scenario
//! and the model, the transforms that keep them feasible, and the settings
//! that apply a set of values to the scenario.
//!
//! Names: `NAME.stiffness` / `NAME.damping` / `NAME.force` (the values
//! k1…k7 / c1…c7 of crush component `NAME`, or the forces of its
//! force–deflection curve; the bare word where one crush component has
//! that curve, see [`curve_names`]),
//! a dotted scenario entry holding a number or a list of numbers
//! (`components.front_end.unloading_stiffness`), or a spec parameter (`k_f`).
//!
//! Bounds by transform: a positive value is fitted as its logarithm (it
//! stays positive: stiffness ≥ 0), a list named `…breakpoints` as the
//! logarithms of its first value and its increments (it stays ordered),
//! anything else as is.

use lagrangian_sim::scenario::{ModelNames, Override};

/// Why the names of `--fit` do not resolve to entries: the name, and what
/// the scenario and the model have instead.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParameterError {
    /// A curve's word, and the scenario has no crush component.
    #[error("--fit {name}: the scenario has no crush component (type = \"crush\")")]
    NoCrushComponent {
        /// The name given.
        name: String,
    },
    /// A curve's word that no crush component has.
    #[error(
        "--fit {name}: no crush component of the scenario has a {name} curve (`{name}_values`); the curves it has: {}",
        quoted(.curves)
    )]
    NoSuchCurve {
        /// The name given.
        name: String,
        /// The curves the scenario has.
        curves: Vec<String>,
    },
    /// A curve's word that several crush components have.
    #[error(
        "--fit {name}: several crush components have a {name} curve; name one: {}",
        quoted(.curves)
    )]
    SeveralCurves {
        /// The name given.
        name: String,
        /// The curves of that word.
        curves: Vec<String>,
    },
    /// A crush component's curve that it does not have.
    #[error(
        "--fit {name}: crush component `{component}` has no {what} curve (`{what}_values`); the curves it has: {}",
        quoted(.curves)
    )]
    ComponentLacksCurve {
        /// The name given.
        name: String,
        /// The component.
        component: String,
        /// The curve's word.
        what: String,
        /// The curves it has.
        curves: Vec<String>,
    },
    /// A name that is nothing the fit knows.
    #[error(
        "--fit {name}: not a spec parameter ({}), a crush curve of the scenario ({}), or an entry of the scenario{}",
        quoted(.parameters),
        quoted_or_none(.curves),
        suggestion(.closest)
    )]
    Unknown {
        /// The name given.
        name: String,
        /// The spec's parameters.
        parameters: Vec<String>,
        /// The scenario's crush curves.
        curves: Vec<String>,
        /// The accepted name closest to it.
        closest: Option<String>,
    },
    /// An entry that is neither a number nor a list.
    #[error("--fit {name}: `{key}` is not a number ({value})")]
    NotANumber {
        /// The name given.
        name: String,
        /// The scenario key.
        key: String,
        /// Its value, as TOML.
        value: String,
    },
    /// A list with something other than numbers.
    #[error("--fit {name}: `{key}` holds something other than numbers")]
    NotNumbers {
        /// The name given.
        name: String,
        /// The scenario key.
        key: String,
    },
    /// Breakpoints that are not positive and increasing.
    #[error("--fit {name}: `{key}` must be positive and increasing")]
    NotIncreasing {
        /// The name given.
        name: String,
        /// The scenario key.
        key: String,
    },
    /// An entry named twice.
    #[error("--fit: `{label}` is named twice")]
    NamedTwice {
        /// The entry's label.
        label: String,
    },
    /// No entry.
    #[error("--fit: nothing to fit")]
    Nothing,
}

/// How an entry's value maps to the unconstrained variable of the fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Transform {
    /// `u = p`.
    Identity,
    /// `u = ln p` (p > 0).
    Log,
    /// `u = ln(p_i − p_{i−1})` (`ln p_0` for the first): an increasing list.
    Increment,
}

/// One scalar the fit varies.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Scenario key (`components.front_end.stiffness_values`) or parameter name.
    pub key: String,
    /// Position in the list, for list entries.
    pub index: Option<usize>,
    /// Name in reports (`front_end.k3`, `k_f`).
    pub label: String,
    /// How the fit variable maps to the value: keeps a positive value
    /// positive and an ordered list ordered.
    pub transform: Transform,
}

/// A key and the values of everything at it (all entries of a list).
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// Scenario key or parameter name, as in [`Entry::key`]; one slot per key.
    pub key: String,
    /// `true` when the key holds a list (set as `key=[a, b, …]`), `false`
    /// for a single number.
    pub is_list: bool,
    /// The values at the key in the base scenario (one for a number), in
    /// the entry's own units; entries not fitted keep these.
    pub base: Vec<f64>,
}

/// The fitted entries and the slots they live in.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameters {
    /// The scalars the fit varies, in the order of `--fit` (a list's
    /// entries in list order); no two have the same label.
    pub entries: Vec<Entry>,
    /// The keys those entries are in, each once; every entry's key has
    /// its slot.
    pub slots: Vec<Slot>,
}

/// The crush components of a scenario document.
fn crush_components(document: &toml::Table) -> Vec<String> {
    document
        .get("components")
        .and_then(toml::Value::as_table)
        .map(|c| {
            c.iter()
                .filter(|(_, v)| v.get("type").and_then(toml::Value::as_str) == Some("crush"))
                .map(|(k, _)| k.clone())
                .collect()
        })
        .unwrap_or_default()
}

fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

fn lookup<'a>(document: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut table = Some(document);
    let mut value = None;
    for part in lagrangian_sim::key_segments(key) {
        value = table.and_then(|t| t.get(&part));
        table = value.and_then(toml::Value::as_table);
    }
    value
}

/// The curves of a crush component that `--fit` names: the word, the
/// scenario entry of its values (`{component}.{entry}`) and the letter of
/// its labels (`front_end.k3`).
const CURVES: [(&str, &str, &str); 3] = [
    ("stiffness", "stiffness_values", "k"),
    ("damping", "damping_values", "c"),
    ("force", "force_values", "F"),
];

/// One curve of a crush component that `--fit` accepts by name.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveName {
    /// The crush component (`front_end`).
    pub component: String,
    /// `stiffness`, `damping` or `force`.
    pub what: &'static str,
}

impl CurveName {
    /// `front_end.stiffness`: the name `--fit` takes.
    pub fn name(&self) -> String {
        format!("{}.{}", self.component, self.what)
    }

    fn entry(&self) -> (String, String) {
        let (_, values, letter) = CURVES
            .iter()
            .find(|(what, _, _)| *what == self.what)
            .expect("a curve's word is one of CURVES");
        (
            format!("components.{}.{values}", self.component),
            format!("{}.{letter}", self.component),
        )
    }
}

/// The curves of the crush components of `document` that `--fit` accepts
/// (a curve is there when its `…_values` entry is), in component order:
/// the one list that resolving a name and every suggestion come from.
pub fn curve_names(document: &toml::Table) -> Vec<CurveName> {
    let mut names = Vec::new();
    let components = document.get("components").and_then(toml::Value::as_table);
    for component in crush_components(document) {
        let section = components.and_then(|c| c.get(&component));
        for (what, values, _) in CURVES {
            if section.and_then(|s| s.get(values)).is_some() {
                names.push(CurveName {
                    component: component.clone(),
                    what,
                });
            }
        }
    }
    names
}

/// The names `--fit` accepts that the messages suggest: the crush curves
/// (`front_end.stiffness`; the bare word too where one component has that
/// curve), then the spec parameters.
pub fn accepted_names(document: &toml::Table, model: &ModelNames) -> Vec<String> {
    let curves = curve_names(document);
    let mut names: Vec<String> = curves.iter().map(CurveName::name).collect();
    for (what, _, _) in CURVES {
        if curves.iter().filter(|c| c.what == what).count() == 1 {
            names.push(what.to_string());
        }
    }
    names.extend(model.parameters.iter().cloned());
    names
}

/// `` `a`, `b` `` for a message.
fn quoted(names: &[String]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    quoted.join(", ")
}

/// [`quoted`], or `it has none`.
fn quoted_or_none(names: &[String]) -> String {
    match names.is_empty() {
        true => "it has none".to_string(),
        false => quoted(names),
    }
}

/// `; did you mean `best`?`, or nothing.
fn suggestion(closest: &Option<String>) -> String {
    (closest.as_ref()).map_or(String::new(), |best| format!("; did you mean `{best}`?"))
}

/// The scenario key of the values a curve name stands for
/// (`front_end.stiffness`: the `stiffness_values` of crush component
/// `front_end`; a bare `stiffness`: those of the only crush component with
/// a stiffness curve) and the prefix of their labels (`front_end.k`);
/// `None` for a name that is no curve's.
fn crush_values_key(
    name: &str,
    document: &toml::Table,
) -> Result<Option<(String, String)>, ParameterError> {
    let curves = curve_names(document);
    let is_word = |w: &str| CURVES.iter().any(|(what, _, _)| *what == w);
    let names_of = |c: &[&CurveName]| c.iter().map(|c| c.name()).collect::<Vec<_>>();
    let all: Vec<&CurveName> = curves.iter().collect();
    let name_given = name.to_string();
    if is_word(name) {
        let holders: Vec<&CurveName> = curves.iter().filter(|c| c.what == name).collect();
        return match holders.as_slice() {
            [one] => Ok(Some(one.entry())),
            [] if crush_components(document).is_empty() => {
                Err(ParameterError::NoCrushComponent { name: name_given })
            }
            [] => Err(ParameterError::NoSuchCurve {
                name: name_given,
                curves: names_of(&all),
            }),
            many => Err(ParameterError::SeveralCurves {
                name: name_given,
                curves: names_of(many),
            }),
        };
    }
    let Some((component, what)) = name.split_once('.') else {
        return Ok(None);
    };
    if !is_word(what) || !crush_components(document).iter().any(|c| c == component) {
        return Ok(None);
    }
    match curves
        .iter()
        .find(|c| c.component == component && c.what == what)
    {
        Some(curve) => Ok(Some(curve.entry())),
        None => {
            let own: Vec<&CurveName> = curves.iter().filter(|c| c.component == component).collect();
            Err(ParameterError::ComponentLacksCurve {
                name: name_given,
                component: component.to_string(),
                what: what.to_string(),
                curves: names_of(&own),
            })
        }
    }
}

/// The error for a `--fit` name that is nothing the fit knows, with the
/// names it accepts (and the closest of them).
fn unknown_name(name: &str, document: &toml::Table, model: &ModelNames) -> ParameterError {
    let curves: Vec<String> = curve_names(document).iter().map(CurveName::name).collect();
    let accepted = accepted_names(document, model);
    let closest = lagrangian_runtime::names::closest(name, accepted.iter().map(String::as_str));
    ParameterError::Unknown {
        name: name.to_string(),
        parameters: model.parameters.clone(),
        curves,
        closest: closest.map(str::to_string),
    }
}

impl Parameters {
    /// Resolves `names` against the scenario `document` and the model's
    /// parameter names and defaults.
    pub fn resolve(
        names: &[String],
        document: &toml::Table,
        model: &ModelNames,
        defaults: &[f64],
    ) -> Result<Parameters, ParameterError> {
        let mut parameters = Parameters {
            entries: Vec::new(),
            slots: Vec::new(),
        };
        for name in names {
            let name = name.trim();
            if let Some(p) = model.parameters.iter().position(|p| p == name) {
                let base = document
                    .get("parameters")
                    .and_then(|t| t.get(name))
                    .and_then(number)
                    .unwrap_or(defaults[p]);
                parameters.push_scalar(name.to_string(), name.to_string(), base);
                continue;
            }
            let (key, prefix) = crush_values_key(name, document)?
                .unwrap_or_else(|| (name.to_string(), String::new()));
            let value =
                lookup(document, &key).ok_or_else(|| unknown_name(name, document, model))?;
            match value {
                toml::Value::Array(items) => parameters.push_list(name, key, &prefix, items)?,
                other => {
                    let base = number(other).ok_or_else(|| ParameterError::NotANumber {
                        name: name.to_string(),
                        key: key.clone(),
                        value: other.to_string(),
                    })?;
                    parameters.push_scalar(key.clone(), key, base);
                }
            }
        }
        let mut seen = std::collections::HashSet::new();
        if let Some(dup) = parameters
            .entries
            .iter()
            .find(|e| !seen.insert(e.label.clone()))
        {
            return Err(ParameterError::NamedTwice {
                label: dup.label.clone(),
            });
        }
        if parameters.entries.is_empty() {
            return Err(ParameterError::Nothing);
        }
        Ok(parameters)
    }

    /// Every number of the list at `key` as an entry, labelled `{prefix}1`,
    /// `{prefix}2`, … (`key[0]`, … without a prefix); a list named
    /// `…breakpoints` must be positive and increasing, and stays so.
    fn push_list(
        &mut self,
        name: &str,
        key: String,
        prefix: &str,
        items: &[toml::Value],
    ) -> Result<(), ParameterError> {
        let base: Vec<f64> = items
            .iter()
            .map(number)
            .collect::<Option<_>>()
            .ok_or_else(|| ParameterError::NotNumbers {
                name: name.to_string(),
                key: key.clone(),
            })?;
        let ordered = key.ends_with("breakpoints");
        for (i, _) in base.iter().enumerate() {
            let label = if prefix.is_empty() {
                format!("{key}[{i}]")
            } else {
                format!("{prefix}{}", i + 1)
            };
            self.entries.push(Entry {
                key: key.clone(),
                index: Some(i),
                label,
                transform: if ordered {
                    Transform::Increment
                } else if base[i] > 0.0 {
                    Transform::Log
                } else {
                    Transform::Identity
                },
            });
        }
        if ordered
            && (base.windows(2).any(|w| w[1] <= w[0]) || base.first().is_some_and(|&b| b <= 0.0))
        {
            return Err(ParameterError::NotIncreasing {
                name: name.to_string(),
                key,
            });
        }
        self.slots.push(Slot {
            key,
            is_list: true,
            base,
        });
        Ok(())
    }

    fn push_scalar(&mut self, key: String, label: String, base: f64) {
        self.entries.push(Entry {
            key: key.clone(),
            index: None,
            label,
            transform: if base > 0.0 {
                Transform::Log
            } else {
                Transform::Identity
            },
        });
        self.slots.push(Slot {
            key,
            is_list: false,
            base: vec![base],
        });
    }

    /// The physical values of the entries at the base scenario.
    pub fn base_values(&self) -> Vec<f64> {
        self.entries.iter().map(|e| self.slot_value(e)).collect()
    }

    fn slot_of(&self, entry: &Entry) -> &Slot {
        self.slots
            .iter()
            .find(|s| s.key == entry.key)
            .expect("every entry has its slot")
    }

    fn slot_value(&self, entry: &Entry) -> f64 {
        self.slot_of(entry).base[entry.index.unwrap_or(0)]
    }

    /// The whole slot values with `values` (one per entry) put in place.
    fn slot_values(&self, values: &[f64]) -> Vec<Vec<f64>> {
        let mut out: Vec<Vec<f64>> = self.slots.iter().map(|s| s.base.clone()).collect();
        for (entry, &v) in self.entries.iter().zip(values) {
            let s = self
                .slots
                .iter()
                .position(|s| s.key == entry.key)
                .unwrap_or(0);
            out[s][entry.index.unwrap_or(0)] = v;
        }
        out
    }

    /// Physical values → fit variables.
    pub fn to_unconstrained(&self, values: &[f64]) -> Vec<f64> {
        let full = self.slot_values(values);
        self.entries
            .iter()
            .zip(values)
            .map(|(e, &p)| match e.transform {
                Transform::Identity => p,
                Transform::Log => p.ln(),
                Transform::Increment => {
                    let s = self.slots.iter().position(|s| s.key == e.key).unwrap_or(0);
                    let i = e.index.unwrap_or(0);
                    let previous = if i == 0 { 0.0 } else { full[s][i - 1] };
                    (p - previous).ln()
                }
            })
            .collect()
    }

    /// Fit variables → physical values.
    pub fn to_physical(&self, u: &[f64]) -> Vec<f64> {
        let mut running = std::collections::HashMap::<&str, (usize, f64)>::new();
        let mut out = Vec::with_capacity(u.len());
        for (e, &x) in self.entries.iter().zip(u) {
            out.push(match e.transform {
                Transform::Identity => x,
                Transform::Log => x.exp(),
                Transform::Increment => {
                    let i = e.index.unwrap_or(0);
                    let slot = self.slot_of(e);
                    let previous = match running.get(e.key.as_str()) {
                        Some(&(j, v)) if j + 1 == i => v,
                        _ if i == 0 => 0.0,
                        _ => slot.base[i - 1],
                    };
                    let v = previous + x.exp();
                    running.insert(&e.key, (i, v));
                    v
                }
            });
        }
        out
    }

    /// `key=value` settings that put `values` (one per entry) into the scenario.
    pub fn settings(&self, values: &[f64]) -> Vec<String> {
        self.slots
            .iter()
            .zip(self.slot_values(values))
            .map(|(slot, v)| {
                if slot.is_list {
                    let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
                    format!("{}=[{}]", slot.key, items.join(", "))
                } else {
                    format!("{}={:?}", slot.key, v[0])
                }
            })
            .collect()
    }

    /// The overrides that put `values` (one per entry) into the scenario:
    /// what [`Parameters::settings`] writes, as values.
    pub fn overrides(&self, values: &[f64]) -> Vec<Override> {
        let slots = self.slots.iter().zip(self.slot_values(values));
        slots
            .map(|(slot, v)| match slot.is_list {
                true => {
                    let items = v.iter().map(|&x| toml::Value::Float(x)).collect();
                    Override::value(&slot.key, toml::Value::Array(items))
                }
                false => Override::value(&slot.key, toml::Value::Float(v[0])),
            })
            .collect()
    }

    /// Writes `values` into the scenario document (for the fitted scenario file).
    pub fn write_into(&self, document: &mut toml::Table, values: &[f64], model: &ModelNames) {
        for (slot, v) in self.slots.iter().zip(self.slot_values(values)) {
            let value = if slot.is_list {
                toml::Value::Array(v.iter().map(|&x| toml::Value::Float(x)).collect())
            } else {
                toml::Value::Float(v[0])
            };
            let path: Vec<String> = if model.parameters.contains(&slot.key) {
                vec!["parameters".to_string(), slot.key.clone()]
            } else {
                lagrangian_sim::key_segments(&slot.key)
            };
            let mut table = &mut *document;
            for part in &path[..path.len() - 1] {
                let next = table
                    .entry(part.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                let toml::Value::Table(t) = next else {
                    return;
                };
                table = t;
            }
            table.insert(path[path.len() - 1].to_string(), value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> ModelNames {
        ModelNames {
            parameters: vec!["m".into(), "k_f".into()],
            ..Default::default()
        }
    }

    const SCENARIO: &str = r#"
        [parameters]
        k_f = 3.0e4
        [components.front_end]
        type = "crush"
        stiffness_breakpoints = [0.1, 0.3]
        stiffness_values = [1.0e6, 2.0e6, 3.0e6]
        damping_values = [1.0e3, 2.0e3, 3.0e3]
    "#;

    #[test]
    fn names_resolve_to_entries_and_round_trip_through_the_transforms() {
        let doc: toml::Table = SCENARIO.parse().unwrap();
        let p = Parameters::resolve(
            &[
                "stiffness".into(),
                "k_f".into(),
                "m".into(),
                "components.front_end.stiffness_breakpoints".into(),
            ],
            &doc,
            &names(),
            &[1000.0, 1.0],
        )
        .unwrap();
        let labels: Vec<&str> = p.entries.iter().map(|e| e.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "front_end.k1",
                "front_end.k2",
                "front_end.k3",
                "k_f",
                "m",
                "components.front_end.stiffness_breakpoints[0]",
                "components.front_end.stiffness_breakpoints[1]"
            ]
        );
        let base = p.base_values();
        assert_eq!(base, [1.0e6, 2.0e6, 3.0e6, 3.0e4, 1000.0, 0.1, 0.3]);
        let u = p.to_unconstrained(&base);
        let back = p.to_physical(&u);
        for (a, b) in base.iter().zip(&back) {
            assert!((a / b - 1.0).abs() < 1e-14, "{a} {b}");
        }
        // Any variables give increasing breakpoints.
        let mut wild = u.clone();
        wild[5] = 3.0;
        wild[6] = -5.0;
        let v = p.to_physical(&wild);
        assert!(v[6] > v[5] && v[5] > 0.0);
        assert_eq!(
            p.settings(&base)[0],
            "components.front_end.stiffness_values=[1000000.0, 2000000.0, 3000000.0]"
        );
        assert_eq!(p.settings(&base)[1], "k_f=30000.0");
    }

    #[test]
    fn unknown_and_ambiguous_names_are_refused() {
        let doc: toml::Table = SCENARIO.parse().unwrap();
        let e = Parameters::resolve(&["stifness".into()], &doc, &names(), &[1.0, 1.0]).unwrap_err();
        let e = e.to_string();
        assert!(e.contains("not a spec parameter (`m`, `k_f`)"), "{e}");
        assert!(e.ends_with("did you mean `stiffness`?"), "{e}");
        let e = Parameters::resolve(&["k_f".into(), "k_f".into()], &doc, &names(), &[1.0, 1.0])
            .unwrap_err();
        assert_eq!(e.to_string(), "--fit: `k_f` is named twice");
        let none: toml::Table = "".parse().unwrap();
        let e = Parameters::resolve(&["damping".into()], &none, &names(), &[1.0, 1.0]).unwrap_err();
        let e = e.to_string();
        assert!(e.contains("no crush component"), "{e}");
    }

    #[test]
    fn the_forces_of_a_force_deflection_curve_are_fitted_by_name() {
        let doc: toml::Table = r#"
            [components.rails]
            type = "crush"
            force_breakpoints = [0.1, 0.6]
            force_values = [1.8e5, 2.2e5]
        "#
        .parse()
        .unwrap();
        let p = Parameters::resolve(&["rails.force".into()], &doc, &names(), &[1.0, 1.0]);
        let p = p.unwrap();
        let labels: Vec<&str> = p.entries.iter().map(|e| e.label.as_str()).collect();
        assert_eq!(labels, ["rails.F1", "rails.F2"]);
        let base = p.base_values();
        assert_eq!(
            p.settings(&base)[0],
            "components.rails.force_values=[180000.0, 220000.0]"
        );
    }

    /// Scenarios whose crush components have different curves: every name
    /// a message suggests is one `resolve` accepts, and a curve a
    /// component lacks is refused with the curves it has.
    #[test]
    fn every_suggested_name_is_accepted() {
        let doc: toml::Table = r#"
            [components.front]
            type = "crush"
            stiffness_breakpoints = [0.1]
            stiffness_values = [1.0e6, 2.0e6]
            damping_breakpoints = [1.0]
            damping_values = [0.0, 0.0]
            [components.belt]
            type = "crush"
            force_breakpoints = [0.1, 0.2]
            force_values = [1.0e3, 2.0e3]
            damping_breakpoints = [1.0]
            damping_values = [10.0, 10.0]
            [components.rails]
            type = "crush"
            force_breakpoints = [0.1, 0.2]
            force_values = [1.0e5, 2.0e5]
        "#
        .parse()
        .unwrap();
        let resolve = |name: &str| {
            Parameters::resolve(&[name.into()], &doc, &names(), &[1.0, 1.0])
                .map_err(|e| e.to_string())
        };
        let suggested = |message: &str| -> Vec<String> {
            let (_, list) = message.rsplit_once(": ").unwrap();
            list.split(", ")
                .map(|n| n.trim_matches('`').to_string())
                .collect()
        };
        // One component has a stiffness curve: the bare word is its.
        let p = resolve("stiffness").unwrap();
        assert_eq!(p.entries[0].label, "front.k1");
        let e = resolve("damping").unwrap_err();
        assert_eq!(
            e,
            "--fit damping: several crush components have a damping curve; name one: `belt.damping`, `front.damping`"
        );
        let e = resolve("belt.stiffness").unwrap_err();
        assert_eq!(
            e,
            "--fit belt.stiffness: crush component `belt` has no stiffness curve (`stiffness_values`); the curves it has: `belt.damping`, `belt.force`"
        );
        let e2 = resolve("force").unwrap_err();
        for message in [&e, &e2] {
            for name in suggested(message) {
                let p = resolve(&name);
                assert!(p.is_ok(), "{message}: `{name}` is refused: {p:?}");
            }
        }
        // Every name the unknown-name message and the accepted list give.
        let e = resolve("stifness").unwrap_err();
        assert!(e.ends_with("did you mean `stiffness`?"), "{e}");
        for name in accepted_names(&doc, &names()) {
            assert!(resolve(&name).is_ok(), "`{name}` is listed but refused");
        }
        let listed = e.split('(').nth(2).unwrap().split(')').next().unwrap();
        for name in listed.split(", ") {
            assert!(resolve(name.trim_matches('`')).is_ok(), "{e}: {name}");
        }
    }
}
