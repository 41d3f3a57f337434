//! A linearization as JSON (one key per entry of [`FIELDS`]) and as
//! markdown tables.

use super::{Linearization, Mode, ModeKind};
use nalgebra::DMatrix;
use serde_json::{Value, json};

/// A key of the JSON report and how its value is made.
pub type Field = (&'static str, fn(&Linearization) -> Value);

/// The keys of the JSON report, in order: the one list that
/// [`json`] writes.
pub const FIELDS: [Field; 10] = [
    ("state_names", |l| json!(l.state_names)),
    ("input_names", |l| json!(input_names(l))),
    ("A", |l| rows(&l.a)),
    ("B", |l| rows(&l.b)),
    ("B_columns", |l| json!(column_descriptions(l))),
    ("operating_point", operating_point),
    ("A_from", |l| json!(l.source.name())),
    ("natural_frequencies_hz", |l| {
        json!(l.modes.iter().map(|m| m.frequency_hz).collect::<Vec<_>>())
    }),
    ("damping_ratios", |l| {
        json!(
            l.modes
                .iter()
                .map(|m| finite(m.damping_ratio))
                .collect::<Vec<_>>()
        )
    }),
    ("modes", |l| {
        json!(l.modes.iter().map(mode).collect::<Vec<_>>())
    }),
];

/// The linearization as one JSON object with the keys of [`FIELDS`].
pub fn json(linearization: &Linearization) -> Value {
    let mut object = serde_json::Map::new();
    for (key, value) in FIELDS {
        object.insert(key.to_string(), value(linearization));
    }
    Value::Object(object)
}

fn input_names(l: &Linearization) -> Vec<&str> {
    l.inputs.iter().map(|c| c.name.as_str()).collect()
}

/// What each column of `B` is, in words.
fn column_descriptions(l: &Linearization) -> Vec<String> {
    (l.inputs.iter())
        .map(|c| {
            let held = match c.source.as_str() {
                super::UNBOUND => "unbound: held at 0".to_string(),
                source => format!("the constant of `{source}`"),
            };
            format!("∂ẋ/∂{0} at {0} = {1} ({held})", c.name, c.value)
        })
        .collect()
}

fn rows(m: &DMatrix<f64>) -> Value {
    json!(
        m.row_iter()
            .map(|r| r.iter().copied().collect::<Vec<_>>())
            .collect::<Vec<_>>()
    )
}

/// A number, or null for NaN (the damping ratio of a rigid-body mode).
fn finite(x: f64) -> Value {
    match x.is_finite() {
        true => json!(x),
        false => Value::Null,
    }
}

/// `{name: value}` over the coordinates.
fn named(l: &Linearization, values: &[f64]) -> Value {
    let object = (l.state_names.iter().zip(values))
        .map(|(name, &v)| (name.clone(), json!(v)))
        .collect();
    Value::Object(object)
}

fn operating_point(l: &Linearization) -> Value {
    let point = &l.operating_point;
    let equilibrium = point.equilibrium.as_ref().map(|e| {
        let moved: Vec<f64> = point.q.iter().zip(&e.start).map(|(q, s)| q - s).collect();
        json!({
            "solved_for": e.solved.iter().map(|&i| &l.state_names[i]).collect::<Vec<_>>(),
            "start": named(l, &e.start),
            "moved": named(l, &moved),
        })
    });
    let projection = point.projection.as_ref().map(|given| {
        let p = &given.projection;
        json!({
            "given_q": named(l, &given.q),
            "given_qd": named(l, &given.qd),
            "residual_before": p.residual_before,
            "coordinate_change": p.coordinate_change,
            "velocity_change": p.velocity_change,
            "iterations": p.iterations,
        })
    });
    json!({
        "t": 0.0,
        "q": named(l, &point.q),
        "qd": named(l, &point.qd),
        "qdd": named(l, &point.qdd),
        "equilibrium": equilibrium,
        "projection": projection,
    })
}

fn mode(m: &Mode) -> Value {
    json!({
        "kind": m.kind.name(),
        "description": m.kind.description(),
        "frequency_hz": m.frequency_hz,
        "damping_ratio": finite(m.damping_ratio),
        "eigenvalue": { "re": m.eigenvalue.re, "im": m.eigenvalue.im },
    })
}

/// The linearization as markdown: the operating point, the modes, `A`
/// and `B`, under the heading `title`.
pub fn markdown(l: &Linearization, title: &str) -> String {
    let mut text = format!("# Linearization of {title}\n\n## Operating point (t = 0)\n\n");
    text.push_str(&operating_point_table(l));
    text.push_str(&projection_note(l));
    text.push_str("\n## Modes\n\n| # | frequency [Hz] | damping ratio | eigenvalue [1/s] | kind |\n|---|---|---|---|---|\n");
    for (k, m) in l.modes.iter().enumerate() {
        let ratio = finite(m.damping_ratio).as_f64().map_or("—".into(), number);
        let eigenvalue = match m.eigenvalue.im {
            0.0 => number(m.eigenvalue.re),
            im => format!("{} ± {}i", number(m.eigenvalue.re), number(im)),
        };
        text.push_str(&format!(
            "| {} | {} | {ratio} | {eigenvalue} | {} |\n",
            k + 1,
            number(m.frequency_hz),
            m.kind.description(),
        ));
    }
    if l.modes.iter().any(|m| m.kind == ModeKind::Unstable) {
        text.push_str("\nThe operating point is unstable: a mode grows.\n");
    }
    if !l.constraints.is_empty() {
        text.push_str(&format!(
            "\nThe modes of the motion on the constraints ({}); A below is that of the \
             constrained accelerations, whose further eigenvalues (zero) leave them.\n",
            l.constraints.join(", ")
        ));
    }
    text.push_str(&format!(
        "\n## A = ∂ẋ/∂x ({}; x = (q, q̇))\n\n",
        l.source.name()
    ));
    text.push_str(&matrix_table(&l.a, &l.state_names, &l.state_names));
    text.push_str("\n## B = ∂ẋ/∂u\n\n");
    match l.inputs.is_empty() {
        true => text.push_str("No inputs: every input of the dynamics is part of the system.\n"),
        false => {
            text.push_str(&matrix_table(&l.b, &l.state_names, &input_names(l)));
            text.push('\n');
            for description in column_descriptions(l) {
                text.push_str(&format!("- {description}\n"));
            }
        }
    }
    text
}

/// What the projection of a given state onto the constraints changed, as
/// `simulate`'s summary says it (empty without one).
pub fn projection_note(l: &Linearization) -> String {
    let Some(given) = &l.operating_point.projection else {
        return String::new();
    };
    let p = &given.projection;
    format!(
        "\nThe state given was projected onto the constraints ({}): |g| was {:.1e}; |Δq| = {:.1e}, |Δq̇| = {:.1e}. The table is the projected state.\n",
        l.constraints.join(", "),
        p.residual_before,
        p.coordinate_change,
        p.velocity_change
    )
}

fn operating_point_table(l: &Linearization) -> String {
    let point = &l.operating_point;
    let mut text = String::from(
        "| coordinate | q | q̇ | q̈ | moved from the start by |\n|---|---|---|---|---|\n",
    );
    for (i, name) in l.state_names.iter().take(point.q.len()).enumerate() {
        let moved = match &point.equilibrium {
            Some(e) if e.solved.contains(&i) => number(point.q[i] - e.start[i]),
            Some(_) => "held".to_string(),
            None => "—".to_string(),
        };
        text.push_str(&format!(
            "| {name} | {} | {} | {} | {moved} |\n",
            number(point.q[i]),
            number(point.qd[i]),
            number(point.qdd[i])
        ));
    }
    text
}

fn matrix_table<S: AsRef<str>>(m: &DMatrix<f64>, rows: &[String], columns: &[S]) -> String {
    let mut text = String::from("| |");
    for c in columns {
        text.push_str(&format!(" {} |", c.as_ref()));
    }
    text.push_str(&format!("\n|---|{}\n", "---|".repeat(columns.len())));
    for (name, row) in rows.iter().zip(m.row_iter()) {
        text.push_str(&format!("| {name} |"));
        for x in row.iter() {
            text.push_str(&format!(" {} |", number(*x)));
        }
        text.push('\n');
    }
    text
}

/// Six significant digits, in scientific notation outside [10⁻³, 10⁶).
fn number(x: f64) -> String {
    let size = x.abs();
    if x == 0.0 {
        "0".to_string()
    } else if (1e-3..1e6).contains(&size) {
        let decimals = (5 - size.log10().floor() as i32).max(0) as usize;
        let text = format!("{x:.decimals$}");
        match text.contains('.') {
            true => text.trim_end_matches('0').trim_end_matches('.').to_string(),
            false => text,
        }
    } else {
        format!("{x:.5e}")
    }
}
