use super::channels::filtered;
use super::crush::{AFTER_CONTACT, crush_lines};
use super::panels::{force_deflection_panel, panels_of};
use super::*;
use lagrangian_sim::ode::{Method, Stats};
use lagrangian_sim::scenario::{Column, Role};
use lagrangian_sim::simulate::{Sample, Summary};

fn sample(components: Vec<f64>) -> Sample {
    Sample {
        t: 0.0,
        q: Vec::new(),
        v: Vec::new(),
        a: Vec::new(),
        kinetic: 0.0,
        potential: 0.0,
        dissipated: 0.0,
        external_work: 0.0,
        inputs: Vec::new(),
        outputs: Vec::new(),
        components,
        multipliers: Vec::new(),
        residuals: Vec::new(),
        crush: None,
    }
}

#[test]
fn each_crush_element_is_drawn_against_its_own_deflection() {
    // Columns: a.force, a.deflection, b.deflection, b.force.
    let samples = [
        sample(vec![1e3, 0.1, 0.5, 4e3]),
        sample(vec![2e3, 0.2, 0.6, 5e3]),
    ];
    let elements = [("a".to_string(), 0, 1), ("b".to_string(), 3, 2)];
    let panel = force_deflection_panel(&samples, &elements);
    assert_eq!(panel.title, "Crush force against crush");
    let lines: Vec<(&str, &[(f64, f64)])> = (panel.lines.iter())
        .map(|l| (l.name.as_str(), l.points.as_slice()))
        .collect();
    assert_eq!(
        lines,
        [
            ("a", [(0.1, 1.0), (0.2, 2.0)].as_slice()),
            ("b", [(0.5, 4.0), (0.6, 5.0)].as_slice()),
        ]
    );
}

/// A signal of one column.
fn signal(name: &str, column: Column, unit: &str) -> Signal {
    Signal {
        name: name.into(),
        terms: vec![(if name.starts_with('-') { -1.0 } else { 1.0 }, column)],
        offset: 0.0,
        unit: Some(unit.into()),
    }
}

fn channel(role: Role, name: &str, column: Column, unit: &str) -> Channel {
    Channel {
        role,
        signal: signal(name, column, unit),
        cfc: lagrangian_sim::pulse::cfc::DEFAULT_CLASS,
    }
}

/// Two coordinates `x`, `theta` and an output `belt`, sampled every
/// millisecond for 200 ms; the contact ends at 120 ms with 0.3 m of
/// permanent crush.
fn result() -> SimulationResult {
    let samples = (0..=200)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let w = 20.0;
            Sample {
                t,
                q: vec![(w * t).sin(), 0.1 * t],
                v: vec![w * (w * t).cos(), 0.1],
                a: vec![-w * w * (w * t).sin(), 0.0],
                outputs: vec![1e3 * t],
                ..sample(vec![2e3 * t, t])
            }
        })
        .collect();
    SimulationResult {
        model: "Test".into(),
        coordinates: vec!["x".into(), "theta".into()],
        input_columns: Vec::new(),
        output_columns: vec!["belt".into()],
        component_columns: Vec::new(),
        initial_q: vec![0.0, 0.0],
        samples,
        stats: Stats::default(),
        events: Vec::new(),
        summary: Summary {
            end_of_contact_s: Some(0.12),
            permanent_crush_m: Some(0.3),
            ..Summary::EMPTY
        },
        method: Method::Dopri5,
        warnings: Vec::new(),
        constraints: None,
    }
}

/// A crush channel, channels of every role, pitch and a crush element.
fn setup() -> PlotSetup {
    PlotSetup {
        crush: Some(signal("x", Column::Coordinate(0), "m")),
        channels: vec![
            channel(Role::Displacement, "x", Column::Coordinate(0), "m"),
            channel(Role::Displacement, "theta", Column::Coordinate(1), "rad"),
            channel(Role::Velocity, "x_dot", Column::Velocity(0), "m/s"),
            channel(
                Role::Acceleration,
                "x_ddot",
                Column::Acceleration(0),
                "m/s^2",
            ),
            channel(Role::Force, "belt", Column::Output(0), "N"),
            channel(
                Role::Acceleration,
                "-x_ddot",
                Column::Acceleration(0),
                "m/s^2",
            ),
        ],
        pitch: vec![1],
        force_deflection: vec![("front".into(), 0, 1)],
        g: 10.0,
        title: "Test — a scenario".into(),
    }
}

#[test]
fn panels_follow_the_channel_groups_with_titles_labels_and_legends() {
    let panels = panels_of(&result(), &setup());
    let shown: Vec<(&str, &str, Vec<&str>)> = (panels.iter())
        .map(|p| {
            let names = p.lines.iter().map(|l| l.name.as_str()).collect();
            (p.title.as_str(), p.y_label.as_str(), names)
        })
        .collect();
    let energies = vec![
        "kinetic",
        "potential − V(0)",
        "dissipated by D",
        "absorbed by inputs",
    ];
    assert_eq!(
        shown,
        [
            (
                "Crush",
                "crush [m]",
                vec!["crush", "permanent crush", AFTER_CONTACT]
            ),
            ("Crush rate", "crush rate [m/s]", vec!["crush rate"]),
            (
                "Deceleration",
                "deceleration [g]",
                vec!["deceleration, raw", "deceleration, CFC 60"]
            ),
            // Units differ: in the legend only.
            ("Displacement", "displacement", vec!["x [m]", "theta [rad]"]),
            ("Velocity", "velocity [m/s]", vec!["x_dot [m/s]"]),
            (
                "Acceleration",
                "acceleration [g]",
                vec![
                    // Each at its own class: the default, CFC 180.
                    "x_ddot [g], raw",
                    "x_ddot [g], CFC 180",
                    "-x_ddot [g], raw",
                    "-x_ddot [g], CFC 180"
                ]
            ),
            ("Force", "force [kN]", vec!["belt [kN]"]),
            ("Pitch from static equilibrium", "angle [°]", vec!["theta"]),
            ("Energy", "energy [kJ]", energies),
            ("Crush force against crush", "force [kN]", vec!["front"]),
        ]
    );
}

#[test]
fn channel_values_are_drawn_in_their_units_accelerations_in_g_forces_in_kn() {
    let result = result();
    let panels = panels_of(&result, &setup());
    let line = |title: &str, k: usize| {
        let panel = panels.iter().find(|p| p.title == title).unwrap();
        panel.lines[k].points.clone()
    };
    let s = &result.samples[37];
    assert_eq!(line("Displacement", 0)[37], (s.t * 1e3, s.q[0]));
    assert_eq!(line("Force", 0)[37], (s.t * 1e3, s.outputs[0] * 1e-3));
    assert_eq!(line("Acceleration", 0)[37], (s.t * 1e3, s.a[0] / 10.0));
    assert_eq!(line("Acceleration", 2)[37], (s.t * 1e3, -s.a[0] / 10.0));
    assert_eq!(line("Deceleration", 0)[37], (s.t * 1e3, -s.a[0] / 10.0));
}

#[test]
fn every_filtered_line_has_one_point_per_sample() {
    let result = result();
    let panels = panels_of(&result, &setup());
    let filtered: Vec<&Line> = (panels.iter())
        .flat_map(|p| &p.lines)
        .filter(|l| l.name.ends_with("CFC 60") || l.name.ends_with("CFC 180"))
        .collect();
    // The vehicle's deceleration at CFC 60, the two channels at theirs.
    assert_eq!(filtered.len(), 3);
    for line in filtered {
        assert_eq!(line.points.len(), result.samples.len(), "{}", line.name);
        assert_eq!(line.style, Style::Solid);
    }
}

#[test]
fn a_filtered_line_of_uneven_samples_comes_back_at_the_sample_times() {
    // 1 kHz with an event sample between two output times.
    let mut t: Vec<f64> = (0..=100).map(|k| k as f64 * 1e-3).collect();
    t.insert(51, 0.0504);
    let constant = vec![-9.5; t.len()];
    let level = filtered(&t, &constant, 60.0).unwrap();
    assert_eq!(level.len(), t.len());
    assert!(level.iter().all(|&x| (x + 9.5).abs() < 1e-9), "{level:?}");
    // A 1 kHz alternation is far above CFC 60's corner: filtered away.
    let t: Vec<f64> = (0..=200).map(|k| k as f64 * 1e-3).collect();
    let alternating: Vec<f64> = (0..=200)
        .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let smoothed = filtered(&t, &alternating, 60.0).unwrap();
    let inner = &smoothed[50..150];
    assert!(inner.iter().all(|x| x.abs() < 1e-2), "{inner:?}");
}

#[test]
fn the_permanent_crush_starts_at_the_end_of_contact() {
    let t = [0.0, 0.01, 0.02, 0.03, 0.04];
    let crush = [0.0, 0.4, 0.5, 0.45, 0.3];
    let lines = crush_lines(&t, &crush, Some((0.025, 0.48)));
    let names: Vec<&str> = lines.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names, ["crush", "permanent crush", AFTER_CONTACT]);
    assert_eq!(
        lines[0].points,
        [(0.0, 0.0), (10.0, 0.4), (20.0, 0.5), (25.0, 0.48)]
    );
    assert_eq!(lines[1].points, [(25.0, 0.48), (40.0, 0.48)]);
    assert_eq!(lines[2].points, [(25.0, 0.48), (30.0, 0.45), (40.0, 0.3)]);
    assert_eq!(lines[2].style, Style::Dashed);
    assert_eq!(lines[1].style, Style::Solid);
}

#[test]
fn the_crush_is_drawn_whole_while_in_contact_to_the_end() {
    let t = [0.0, 0.01, 0.02];
    let lines = crush_lines(&t, &[0.0, 0.4, 0.5], None);
    assert_eq!(lines.len(), 1);
    assert_eq!(lines[0].name, "crush");
    assert_eq!(lines[0].points, [(0.0, 0.0), (10.0, 0.4), (20.0, 0.5)]);
}

#[test]
fn the_permanent_crush_of_a_run_starts_at_its_end_of_contact() {
    let panels = panels_of(&result(), &setup());
    let permanent = &panels[0].lines[1];
    assert_eq!(permanent.points.first(), Some(&(120.0, 0.3)));
    assert_eq!(permanent.points.last(), Some(&(200.0, 0.3)));
}

#[test]
fn the_grid_grows_by_rows_of_three() {
    // Ten panels: four rows.
    let svg = figure_svg(&result(), &setup()).unwrap();
    let height = 4 * PANEL_SIZE.1 + TITLE_HEIGHT;
    let width = 3 * PANEL_SIZE.0;
    assert!(
        svg.starts_with(&format!("<svg width=\"{width}\" height=\"{height}\"")),
        "{}",
        &svg[..80]
    );
    // Without a crush channel, channels or pitch: the coordinates, their
    // rates and the energies fill one row.
    let bare = PlotSetup {
        g: 10.0,
        ..PlotSetup::default()
    };
    let panels = panels_of(&result(), &bare);
    let titles: Vec<&str> = panels.iter().map(|p| p.title.as_str()).collect();
    assert_eq!(titles, ["Coordinates", "Velocities", "Energy"]);
    let svg = figure_svg(&result(), &bare).unwrap();
    let height = PANEL_SIZE.1 + TITLE_HEIGHT;
    assert!(svg.starts_with(&format!("<svg width=\"{width}\" height=\"{height}\"")));
}

#[test]
fn the_legend_goes_to_the_emptiest_corner() {
    let line = |points: Vec<(f64, f64)>| Line::solid("a", points, 0);
    let bounds = ((0.0, 10.0), (0.0, 1.0));
    // A rise to a plateau: the lower right is empty.
    let plateau = line(
        (0..=10)
            .map(|k| (k as f64, (k as f64 / 3.0).min(1.0)))
            .collect(),
    );
    assert!(matches!(
        legend_corner(&[plateau], bounds),
        SeriesLabelPosition::LowerRight
    ));
    // A pulse near the start: the upper right is empty.
    let pulse = line(
        (0..=10)
            .map(|k| (k as f64, if k == 2 { 1.0 } else { 0.0 }))
            .collect(),
    );
    assert!(matches!(
        legend_corner(&[pulse], bounds),
        SeriesLabelPosition::UpperRight
    ));
}

#[test]
fn a_legend_every_corner_of_whose_panel_has_data_gets_room_of_its_own() {
    // Energies that cross: one falls from the upper left, one rises to
    // the upper right, one stays low: points in every corner.
    let falling = Line::solid(
        "kinetic",
        (0..=20)
            .map(|k| (k as f64, 1.0 - k as f64 / 20.0))
            .collect(),
        0,
    );
    let rising = Line::solid(
        "absorbed",
        (0..=20).map(|k| (k as f64, k as f64 / 20.0)).collect(),
        1,
    );
    let lines = [falling, rising];
    let xs = (0.0, 20.0);
    let (corner, ys) = legend_place(&lines, xs, (0.0, 1.0));
    assert!(ys.1 > 1.0 || ys.0 < 0.0, "{ys:?}");
    assert_eq!(corner_count(&lines, corner, (xs, ys)).1, 0, "{ys:?}");
    // Where a corner is empty, nothing changes.
    let plateau = Line::solid(
        "a",
        (0..=10)
            .map(|k| (k as f64, (k as f64 / 3.0).min(1.0)))
            .collect(),
        0,
    );
    let (_, same) = legend_place(&[plateau], (0.0, 10.0), (0.0, 1.0));
    assert_eq!(same, (0.0, 1.0));
}

#[test]
fn a_tick_at_a_rounding_error_below_zero_reads_zero() {
    assert_eq!(tick_label(&-1e-17), tick_label(&0.0));
    assert!(!tick_label(&-1e-17).starts_with('-'));
    assert_eq!(tick_label(&-0.05), "-0.05");
    assert_eq!(tick_label(&2.5), "2.5");
}

#[test]
fn panels_side_by_side_keep_their_size() {
    let series = vec![("a".to_string(), vec![(0.0, 1.0), (1.0, 2.0)])];
    let panel = ("P".to_string(), "x".to_string(), "y".to_string(), series);
    let svg = panels_svg("Two", &[panel.clone(), panel]).unwrap();
    assert!(
        svg.starts_with("<svg width=\"1400\" height=\"500\""),
        "{}",
        &svg[..60]
    );
}
