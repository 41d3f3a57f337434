//! Scenario files that do not fit their spec or hold values out of range.

use super::*;
use crate::files::{Disk, Files};
use crate::table::TableError;
use std::collections::HashMap;

const SPRING: &str = include_str!("../../../specs/spring_mass_damper.lpm");

/// `text` with the overrides `settings` read and applied, or the message
/// of the first problem.
fn parse_with(
    text: &str,
    file: Option<&Path>,
    names: &ModelNames,
    settings: &[&str],
) -> Result<Scenario, String> {
    let settings = Override::parse_all(settings).map_err(|e| e.to_string())?;
    Scenario::parse(text, file, names, &settings).map_err(|e| e.to_string())
}

/// The message with which `text` (and `settings`) is refused for `spec`.
fn error_for(spec: &str, text: &str, settings: &[&str]) -> String {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(spec).unwrap());
    match parse_with(text, None, &names, settings) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The message with which `text` is refused for the spring–mass–damper.
fn error(text: &str, settings: &[&str]) -> String {
    error_for(SPRING, text, settings)
}

const PUSH: &str = "[components.c]\ntype = \"constant\"\nvalues = { push = 1.0 }\n";

#[test]
fn non_finite_and_out_of_range_numbers_name_their_key() {
    let e = error(
        &format!("[simulation]\nt_end = 0.01\noutput_interval = inf\n{PUSH}"),
        &[],
    );
    assert_eq!(
        e,
        "simulation.output_interval = inf: must be a positive, finite number"
    );
    let e = error(
        &format!("[simulation]\nt_end = 1e300\noutput_interval = 1e-300\n{PUSH}"),
        &[],
    );
    assert_eq!(
        e,
        "simulation.output_interval = 1e-300: gives inf samples over t_end = 1e300 s, more than 1e6; use a longer interval"
    );
    let cases = [
        ("[simulation]\nt_end = inf\n", "simulation.t_end = inf"),
        ("[simulation]\nrtol = nan\n", "simulation.rtol = NaN"),
        ("[simulation]\natol = -inf\n", "simulation.atol = -inf"),
        ("[simulation]\nmax_step = 0.0\n", "simulation.max_step = 0"),
        (
            "[simulation]\nmethod = \"rk4\"\nstep = inf\n",
            "simulation.step = inf",
        ),
        ("[parameters]\nk = nan\n", "parameters.k = NaN"),
        (
            "[initial]\ncoordinates = { x = inf }\n",
            "initial.coordinates.x = inf",
        ),
        (
            "[initial]\nvelocities = { x = nan }\n",
            "initial.velocities.x = NaN",
        ),
    ];
    for (section, key) in cases {
        let e = error(&format!("{section}{PUSH}"), &[]);
        assert!(e.starts_with(&format!("{key}: must be")), "{section}: {e}");
    }
    let e = error(
        "[components.c]\ntype = \"constant\"\nvalues = { push = nan }\n",
        &[],
    );
    assert!(
        e.starts_with("components.c.values.push = NaN: must be"),
        "{e}"
    );
    let e = error(PUSH, &["k=inf"]);
    assert!(e.starts_with("--set k=inf: must be a finite number"), "{e}");
    let e = error("", &["push=-inf"]);
    assert!(e.starts_with("--set push = -inf: must be"), "{e}");
    let weld = "[components.w]\ntype = \"weld\"\ninputs = { moment = \"push\" }\ncurve = [[0.0, 0.0], [1.0, 1.0]]\n";
    let e = error(&format!("{weld}failure_moment = -1.0\n"), &[]);
    assert!(
        e.starts_with("components.w.failure_moment = -1: must be"),
        "{e}"
    );
    let e = error(&format!("{weld}damping = inf\n"), &[]);
    assert!(e.starts_with("components.w.damping = inf: must be"), "{e}");
}

const YARIS: &str = include_str!("../../../specs/yaris_double_pendulum.lpm");

const CRUSH: &str = "type = \"crush\"\ncompression = \"positive\"\nstiffness_breakpoints = [0.1]\nstiffness_values = [1.0, 2.0]\ndamping_breakpoints = [1.0]\ndamping_values = [1.0, 1.0]\n";

#[test]
fn components_need_inputs_of_as_many_arguments_as_they_read() {
    // A crush element or weld reads (x, ẋ); push(t) has one argument.
    let e = error(
        &format!("[components.fe]\ninputs = {{ force = \"push\" }}\n{CRUSH}"),
        &[],
    );
    assert_eq!(
        e,
        "components.fe.inputs.force = \"push\": input `push(t)` has 1 argument, but a crush component needs an input of 2 arguments (the crush coordinate and its rate)"
    );
    let e = error(
        "[components.w]\ntype = \"weld\"\ninputs = { moment = \"push\" }\ncurve = [[0.0, 0.0], [1.0, 1.0]]\nfailure_angle = 0.5\n",
        &[],
    );
    assert!(
        e.starts_with("components.w.inputs.moment = \"push\": input `push(t)` has 1 argument, but a weld component needs an input of 2 arguments"),
        "{e}"
    );
    // The derivative ports too.
    let e = error_for(
        YARIS,
        &format!(
            "[components.fe]\ninputs = {{ force = \"crush\", stiffness = \"barrier_x1\" }}\n{CRUSH}"
        ),
        &[],
    );
    assert!(
        e.starts_with("components.fe.inputs.stiffness = \"barrier_x1\": input `barrier_x1(t)` has 1 argument, but a crush component needs"),
        "{e}"
    );
    // A table is a function of one argument; push() has none.
    let no_arguments = SPRING
        .replace("push(t [s]) [N]", "push() [N]")
        .replace("push(t);", "push();");
    let csv = std::env::temp_dir().join(format!("lpm-arity-{}.csv", std::process::id()));
    std::fs::write(&csv, "t,F\n0,5\n1,100\n").unwrap();
    let e = error_for(
        &no_arguments,
        &format!(
            "[components.b]\ntype = \"table\"\nfile = {:?}\ncolumns = {{ push = \"F\" }}\n",
            csv.display().to_string()
        ),
        &[],
    );
    std::fs::remove_file(&csv).ok();
    assert_eq!(
        e,
        "components.b.columns.push: input `push()` has 0 arguments, but a table component needs an input of 1 argument (the time or abscissa of the table)"
    );
    // A constant takes any arguments.
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(&no_arguments).unwrap());
    parse_with(PUSH, None, &names, &["push=2"]).unwrap();
}

#[test]
fn a_crush_section_with_both_forms_of_its_curve_or_a_bad_gap_names_the_keys() {
    let front = format!("[components.fe]\ninputs = {{ force = \"crush\" }}\n{CRUSH}");
    let e = error_for(
        YARIS,
        &format!("{front}force_breakpoints = [0.1]\nforce_values = [1e5]\n"),
        &[],
    );
    assert!(
        e.starts_with("components.fe: stiffness_breakpoints, stiffness_values (a secant stiffness curve) and force_breakpoints, force_values (a force–deflection curve) are two forms"),
        "{e}"
    );
    // A setting reaches the same check.
    let e = error_for(YARIS, &front, &["components.fe.gap=-0.1"]);
    assert_eq!(
        e,
        "--set components.fe.gap=-0.1: must be a finite number ≥ 0"
    );
    let e = error_for(YARIS, &front.replace("[0.1]", "[0.0]"), &[]);
    assert!(
        e.starts_with("components.fe.stiffness_breakpoints: breakpoint 1 (0) must be a positive"),
        "{e}"
    );
}

#[test]
fn the_weld_metric_names_a_weld_component() {
    let weld = "[components.hinge]\ntype = \"weld\"\ninputs = { moment = \"weld\" }\ncurve = [[0.0, 0.0], [1.0, 1.0]]\n";
    let front = format!("[components.front_end]\ninputs = {{ force = \"crush\" }}\n{CRUSH}");
    let e = error_for(
        YARIS,
        &format!("[metrics]\nweld = \"front_end\"\n{front}{weld}"),
        &[],
    );
    assert_eq!(
        e,
        "metrics.weld = \"front_end\": component `front_end` is a crush component; metrics.weld names a weld component (weld components: hinge)"
    );
    let e = error_for(
        YARIS,
        &format!("[metrics]\nweld = \"front_end\"\n{front}"),
        &[],
    );
    assert!(e.ends_with("(the scenario has none)"), "{e}");
    let e = error_for(YARIS, &format!("[metrics]\nweld = \"hing\"\n{weld}"), &[]);
    assert_eq!(
        e,
        "metrics.weld = \"hing\": the scenario has no component `hing`; did you mean `hinge`?"
    );
}

#[test]
fn overrides_split_at_the_first_equals_sign() {
    let read = |s: &str| Override::parse(s).map_err(|e| e.to_string());
    let k = read(" k = 2 ").unwrap();
    assert_eq!(
        (k.key.as_str(), &k.change),
        ("k", &Change::Set(toml::Value::Float(2.0)))
    );
    let file = read("components.c.file=\"a=b.csv\"").unwrap();
    let quoted = Change::Set(toml::Value::String("a=b.csv".into()));
    assert_eq!(
        (file.key.as_str(), &file.change),
        ("components.c.file", &quoted)
    );
    assert_eq!(
        read("k"),
        Err("--set `k` is not of the form key=value".to_string())
    );
    assert_eq!(
        read("k=2e3").unwrap().change,
        Change::Set(toml::Value::Float(2e3))
    );
    assert_eq!(
        read("k=two"),
        Err("--set k: `two` is not a number".to_string())
    );
    assert_eq!(read("k*=1.5").unwrap().change, Change::Scale(1.5));
    assert_eq!(
        read("k*=inf"),
        Err("--set k*: `inf` is not a finite factor".to_string())
    );
    assert_eq!(read("k*=2").unwrap().path(), KeyPath::new("parameters.k"));
    assert_eq!(read(" k = 2 ").unwrap().text(), "k = 2");
}

/// `simulation.step` is RK4's fixed step and the adaptive methods' first step.
#[test]
fn the_step_setting_applies_to_every_method() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let options = |method: &str| {
        let text = format!("[simulation]\nmethod = \"{method}\"\nstep = 2e-6\n{PUSH}");
        Scenario::parse(&text, None, &names, &[]).unwrap().options
    };
    assert_eq!(options("rk4").fixed_step, Some(2e-6));
    assert_eq!(options("rk4").initial_step, None);
    for method in ["dopri5", "tr-bdf2", "implicit"] {
        assert_eq!(options(method).fixed_step, None, "{method}");
        assert_eq!(options(method).initial_step, Some(2e-6), "{method}");
    }
}

#[test]
fn the_impact_speed_goes_to_every_coordinate_that_moves_with_the_vehicle() {
    let names = ModelNames {
        coordinates: vec!["r".into(), "xb".into(), "xe".into()],
        ..ModelNames::default()
    };
    let text = "[initial]\nspeed = 15.5\nmoving = [\"-r\", \"xb\", \"+xe\"]\nvelocities = {}\n";
    let scenario = Scenario::parse(text, None, &names, &[]).unwrap();
    assert_eq!(
        scenario.initial_velocities,
        [(0, -15.5), (1, 15.5), (2, 15.5)]
    );
    // Sweepable as any entry.
    let scenario = parse_with(text, None, &names, &["initial.speed=10"]).unwrap();
    assert_eq!(scenario.initial_velocities[1], (1, 10.0));
}

#[test]
fn an_impact_speed_needs_its_coordinates_once_each() {
    let e = error("[initial]\nspeed = 15.5\n", &[]);
    assert!(e.starts_with("initial.speed = 15.5: name the coordinates that move with the vehicle in initial.moving"), "{e}");
    let e = error("[initial]\nmoving = [\"x\"]\n", &[]);
    assert_eq!(
        e,
        "initial.moving names coordinates but initial.speed gives them no speed"
    );
    let e = error(
        "[initial]\nspeed = 1.0\nmoving = [\"x\"]\nvelocities = { x = 2.0 }\n",
        &[],
    );
    assert_eq!(
        e,
        "initial.velocities.x and initial.moving both set the velocity of `x`; keep one"
    );
    let e = error("[initial]\nspeed = 1.0\nmoving = [\"x\", \"-x\"]\n", &[]);
    assert_eq!(e, "initial.moving names `x` twice");
    let e = error("[initial]\nspeed = 1.0\nmoving = [\"-y\"]\n", &[]);
    assert!(e.contains("initial.moving: coordinate `y`"), "{e}");
    let e = error("[initial]\nspeed = nan\nmoving = [\"x\"]\n", &[]);
    assert!(e.starts_with("initial.speed = NaN"), "{e}");
}

#[test]
fn channels_name_columns_of_the_trajectory_with_suggestions() {
    let names = ModelNames {
        coordinates: vec!["xa".into(), "xb".into()],
        coordinate_units: vec![Some("m".into()), Some("m".into())],
        outputs: vec!["belt_force".into()],
        output_units: vec![Some("N".into())],
        output_reads: vec![Some(lagrangian_runtime::tape::StateReads {
            velocities: true,
            ..Default::default()
        })],
        ..ModelNames::default()
    };
    let parse =
        |metrics: &str| Scenario::parse(&format!("[metrics]\n{metrics}\n"), None, &names, &[]);
    let scenario = parse("crush = \"xa - xb\"\nacceleration = [\"-xa_ddot\"]\ndisplacement = [\"belt_force\", \"2 * xb\"]").unwrap();
    let crush = scenario.crush.unwrap();
    assert_eq!(crush.of_coordinates(&[0.5, 0.25]), 0.25);
    assert_eq!(crush.unit.as_deref(), Some("m"));
    let channels: Vec<(Role, &str, Option<&str>)> = (scenario.channels.iter())
        .map(|c| (c.role, c.signal.name.as_str(), c.signal.unit.as_deref()))
        .collect();
    assert_eq!(
        channels,
        [
            (Role::Displacement, "belt_force", Some("N")),
            (Role::Displacement, "2 * xb", Some("m")),
            (Role::Acceleration, "-xa_ddot", Some("m/s^2")),
        ]
    );
    let error = |metrics: &str| parse(metrics).unwrap_err().to_string();
    assert_eq!(
        error("acceleration = [\"belt_forse\"]"),
        "metrics.acceleration = \"belt_forse\": column `belt_forse` does not exist in the spec; did you mean `belt_force`?"
    );
    assert!(
        error("crush = \"belt_force\"")
            .contains("metrics.crush = \"belt_force\": output `belt_force` reads velocities (dot)")
    );
    assert!(
        error("crush = \"xa_dot\"").contains("the crush channel is a combination of coordinates")
    );
    assert_eq!(
        error("displacement = [\"xa + belt_force\"]"),
        "metrics.displacement = \"xa + belt_force\": adds quantities of different units (m and N)"
    );
    assert_eq!(
        error("displacement = [\"xa\", \"xa\"]"),
        "metrics.displacement = \"xa\": the channel is listed twice"
    );
    assert!(error("displacement = [\"xa - \"]").contains("a term names no column"));
    assert!(error("displacement = [\"two * xa\"]").contains("`two` is not a number"));
}

#[test]
fn an_unknown_channel_in_a_file_is_reported_at_its_line_and_column() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let text = format!("{PUSH}[metrics]\nacceleration = [\n  \"x_ddot\",\n  \"x_dddot\",\n]\n");
    let file = Path::new("car.toml");
    let e = Scenario::parse(&text, Some(file), &names, &[]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "car.toml:7:3: metrics.acceleration = \"x_dddot\": column `x_dddot` does not exist in the spec; did you mean `x_ddot`?"
    );
}

#[test]
fn metrics_contact_names_crush_components() {
    let e = error(&format!("{PUSH}[metrics]\ncontact = [\"c\"]\n"), &[]);
    assert_eq!(
        e,
        "metrics.contact = \"c\": component `c` is a constant component; metrics.contact names crush components (the scenario has none)"
    );
    let e = error(&format!("{PUSH}[metrics]\ncontact = [\"wall\"]\n"), &[]);
    assert!(
        e.starts_with("metrics.contact = \"wall\": crush component `wall` is not in the scenario"),
        "{e}"
    );
}

#[test]
fn tolerances_outside_a_sensible_range_name_their_key_and_value() {
    let paper_start = "[initial]\nvelocities = { x = -15.5 }\n";
    let cases = [
        (
            "rtol = 0.9",
            "simulation.rtol = 0.9: must be in (0, 0.1]: a looser relative tolerance gives no \
             accurate result (1e-6 to 1e-10 is usual)",
        ),
        (
            "rtol = 1e6",
            "simulation.rtol = 1000000: must be in (0, 0.1]: a looser relative tolerance gives no \
             accurate result (1e-6 to 1e-10 is usual)",
        ),
        ("rtol = 0.0", "simulation.rtol = 0: must be in (0, 0.1]"),
        (
            "atol = 0.0",
            "simulation.atol = 0: must be a positive, finite number",
        ),
        (
            "atol = 1e6",
            "simulation.atol = 1000000: must be small against the state's scale, at most 1.55e-2 \
             (1e-3 × the largest initial coordinate or velocity, 15.5, or 1)",
        ),
        (
            "atol = 0.016",
            "simulation.atol = 0.016: must be small against the state's scale, at most 1.55e-2",
        ),
    ];
    for (setting, message) in cases {
        let text = format!("[simulation]\n{setting}\n{paper_start}{PUSH}");
        let e = error(&text, &[]);
        assert!(e.starts_with(message), "{setting}: {e}");
    }
    // The same through --set, as `lpm simulate --rtol` gives it.
    let e = error(&format!("{paper_start}{PUSH}"), &["simulation.rtol=0.9"]);
    assert!(
        e.starts_with("--set simulation.rtol=0.9: must be in (0, 0.1]"),
        "{e}"
    );
    // At the edges: accepted. A state at rest is scaled by 1.
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    for text in [
        format!("[simulation]\nrtol = 0.1\natol = 0.0155\n{paper_start}{PUSH}"),
        format!("[simulation]\nrtol = 1e-12\natol = 1e-3\n{PUSH}"),
    ] {
        Scenario::parse(&text, None, &names, &[]).unwrap_or_else(|e| panic!("{text}: {e}"));
    }
    let e = error(&format!("[simulation]\natol = 2e-3\n{PUSH}"), &[]);
    assert!(
        e.contains("at most 1.00e-3 (1e-3 × the largest initial coordinate or velocity, 0, or 1)"),
        "{e}"
    );
}

/// `--set` errors name the flag and its value, not the scenario file,
/// whether serde or the checks of the values find them.
#[test]
fn setting_errors_name_the_setting() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let refused = |settings: &[&str]| {
        let file = Some(Path::new("scenarios/x.toml"));
        parse_with(PUSH, file, &names, settings).unwrap_err()
    };
    assert_eq!(
        refused(&["initial.speed="]),
        "--set initial.speed=: invalid type: string \"\", expected f64"
    );
    // The second of two settings is the culprit.
    assert_eq!(
        refused(&["simulation.t_end=0.5", "simulation.rtool=1e-6"]),
        "--set simulation.rtool=1e-6: unknown field `rtool`, expected one of `t_end`, `method`, `rtol`, `atol`, `max_step`, `step`, `output_interval`, `max_steps`, `accelerations`, `time_kinks` (did you mean `rtol`?)"
    );
    assert_eq!(
        refused(&["simulation.t_end=-1"]),
        "--set simulation.t_end=-1: must be a positive, finite number"
    );
    // The file's own mistakes still name the file.
    let e = Scenario::parse(
        "[simulation]\nt_end = -1.0\n",
        Some(Path::new("x.toml")),
        &names,
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("x.toml:2:1: simulation.t_end = -1: must be"),
        "{e}"
    );
}

/// `KEY*=FACTOR` multiplies a parameter (the scenario's value, else the
/// spec's) or every number of an entry, as `sweep --grid` does.
#[test]
fn a_factor_setting_scales_parameters_and_entries() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let parse = |text: &str, settings: &[&str]| parse_with(text, None, &names, settings);
    let k = names.parameters.iter().position(|p| p == "k").unwrap();
    // The spec's k = 100.
    let s = parse(PUSH, &["k*=2.5"]).unwrap();
    assert_eq!(s.parameters, [(k, 250.0)]);
    // The scenario's k = 40, then a second factor on the result.
    let text = format!("[parameters]\nk = 40.0\n{PUSH}");
    let s = parse(&text, &["k*=2", "k *= 0.5"]).unwrap();
    assert_eq!(s.parameters, [(k, 40.0)]);
    // A table of numbers: every one of them.
    let text = format!(
        "[simulation]\nt_end = 2.0\n[initial]\ncoordinates = {{ x = 0.2 }}\nvelocities = {{ x = -3.0 }}\n{PUSH}"
    );
    let s = parse(&text, &["initial.velocities*=2", "simulation.t_end*=1.5"]).unwrap();
    assert_eq!(s.initial_velocities, [(0, -6.0)]);
    assert_eq!(s.initial_coordinates, [(0, 0.2)]);
    assert_eq!(s.t_end, 3.0);
    let refused = |settings: &[&str]| parse(PUSH, settings).unwrap_err().to_string();
    assert_eq!(refused(&["k*=x"]), "--set k*: `x` is not a number");
    assert_eq!(
        refused(&["k*=inf"]),
        "--set k*: `inf` is not a finite factor"
    );
    assert_eq!(
        refused(&["initial.speed*=2"]),
        "--set `initial.speed*=`: the scenario has no such entry to scale"
    );
    assert_eq!(
        refused(&["kk*=2"]),
        "--set: a factor applies to a parameter or a dotted scenario entry; parameter `kk` does not exist in the spec; did you mean `k`?"
    );
}

/// `metrics.classes` gives an acceleration channel its class, as a number
/// or by what it measures (J211-1's class for it); a channel without one
/// takes CFC 180; a class not in J211, a measurement it has no class for
/// or a channel not listed under `acceleration` is refused, naming it.
#[test]
fn acceleration_channels_take_their_class_from_metrics_classes() {
    let names = ModelNames {
        coordinates: vec!["xa".into(), "xb".into()],
        coordinate_units: vec![Some("m".into()), Some("m".into())],
        ..ModelNames::default()
    };
    let parse = |classes: &str| {
        let text = format!(
            "[metrics]\nacceleration = [\"xa_ddot\", \"-xb_ddot\", \"xb_ddot\"]\n\
             displacement = [\"xa\"]\nclasses = {{ {classes} }}\n"
        );
        Scenario::parse(&text, None, &names, &[])
    };
    let scenario = parse("xa_ddot = \"head\", \"-xb_ddot\" = 600").unwrap();
    let classes: Vec<(&str, f64)> = (scenario.channels.iter())
        .map(|c| (c.signal.name.as_str(), c.cfc))
        .collect();
    assert_eq!(
        classes,
        [
            ("xa", 180.0),
            ("xa_ddot", 1000.0),
            ("-xb_ddot", 600.0),
            ("xb_ddot", 180.0)
        ]
    );
    let chest = parse("xb_ddot = \"chest\", xa_ddot = \"structure\"").unwrap();
    assert_eq!(
        (chest.channels[1].cfc, chest.channels[3].cfc),
        (60.0, 180.0)
    );
    let error = |classes: &str| parse(classes).unwrap_err().to_string();
    assert_eq!(
        error("xa_ddot = 100"),
        "metrics.classes.\"xa_ddot\" = 100: not a filter class of SAE J211-1 (60, 180, 600 or 1000)"
    );
    assert!(
        error("xa_ddot = \"knee\"").starts_with(
            "metrics.classes.\"xa_ddot\" = \"knee\": not a measurement J211-1 gives a class for; \
             one of head (1000), neck_force (1000)"
        ),
        "{}",
        error("xa_ddot = \"knee\"")
    );
    assert_eq!(
        error("xa = 60"),
        "metrics.classes.\"xa\": not a channel of metrics.acceleration (`xa_ddot`, `-xb_ddot`, \
         `xb_ddot`); a filter class is given to an acceleration channel, by its name as listed there"
    );
    assert!(error("xa_ddot = true").contains("a filter class (60, 180, 600, 1000)"));
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
        let text = self.text(path).map_err(|e| TableError::Read {
            file: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Table::parse(path, &text).map(Arc::new)
    }
}

#[test]
fn a_scenario_reads_itself_and_its_tables_from_the_hosts_files() {
    use crate::scenario::{BaseScenario, ModelNames, Override, Scenario};
    let spec = SPRING;
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
fn quantities_with_units_read_as_their_si_values() {
    let yaris = ModelNames::of_interpreted(&lagrangian_core::interpret(YARIS).unwrap());
    let crush = |speed: &str, forces: &str, t_end: &str| {
        let text = format!(
            "[simulation]\nt_end = {t_end}\n[initial]\nspeed = {speed}\nmoving = [\"r\"]\n\
             [components.fe]\ntype = \"crush\"\ninputs = {{ force = \"crush\" }}\ncompression = \"negative\"\n\
             force_breakpoints = [\"100 mm\", 0.5]\nforce_values = {forces}\n\
             damping_breakpoints = [\"1 m/s\"]\ndamping_values = [\"2 kN*s/m\", 2000]\n"
        );
        let scenario = Scenario::parse(&text, None, &yaris, &[]).unwrap_or_else(|e| panic!("{e}"));
        format!(
            "{:?}",
            (
                scenario.initial_velocities,
                scenario.options,
                scenario.inputs
            )
        )
    };
    // 56 km/h = 56/3.6 m/s; 4 MN; 0.12 s.
    assert_eq!(
        crush("\"56 km/h\"", "[\"4 MN\", \"4000 kN\"]", "\"120 ms\""),
        crush(&format!("{:?}", 56.0 / 3.6), "[4e6, 4e6]", "0.12")
    );
    // A parameter in the unit the spec declares (`m [kg]`), also from --set.
    let spring = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let m = |text: &str, settings: &[&str]| {
        let s = parse_with(text, None, &spring, settings).unwrap_or_else(|e| panic!("{e}"));
        s.parameters
    };
    assert_eq!(
        m("[parameters]\nm = \"1.2 t\"\n", &[]),
        m("[parameters]\nm = 1200.0\n", &[])
    );
    assert_eq!(m("", &["m=\"850 g\""]), m("", &["m=0.85"]));
    assert_eq!(m("", &["m=850 g"]), m("", &["m=0.85"]));
    // An input's constant, from a constant section or --set, in its unit.
    let push = |text: &str, settings: &[&str]| {
        let s = parse_with(text, None, &spring, settings).unwrap_or_else(|e| panic!("{e}"));
        format!("{:?}", s.inputs)
    };
    let constant = |value: &str| {
        format!("[components.c]\ntype = \"constant\"\nvalues = {{ push = {value} }}\n")
    };
    assert_eq!(
        push(&constant("\"2 kN\""), &[]),
        push(&constant("2000.0"), &[])
    );
    assert_eq!(push("", &["push=2 kN"]), push("", &["push=2000"]));
    // A factor scales the SI value; a dotted --set takes a quantity too.
    let speed = |text: &str, settings: &[&str]| {
        let s = parse_with(text, None, &yaris, settings).unwrap_or_else(|e| panic!("{e}"));
        s.initial_velocities
    };
    let moving = "[initial]\nmoving = [\"r\"]\nspeed = \"36 km/h\"\n";
    assert_eq!(speed(moving, &["initial.speed*=2"]), vec![(0, 20.0)]);
    assert_eq!(speed(moving, &["initial.speed=72 km/h"]), vec![(0, 20.0)]);
}

#[test]
fn a_quantity_in_the_wrong_unit_is_refused_at_its_entry() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let text = "[simulation]\nt_end = 0.1\n\n[initial]\nspeed = \"56 km\"\n";
    let e = Scenario::parse(text, Some(Path::new("s.toml")), &names, &[]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "s.toml:5:9: initial.speed = \"56 km\": km is a length, but this entry needs a velocity (m/s)"
    );
    assert_eq!(
        error("", &["simulation.t_end=\"5 kg\""]),
        "--set simulation.t_end=\"5 kg\": kg is a mass, but this entry needs a time (s)"
    );
    assert_eq!(
        error("[parameters]\nk = \"3 kN\"\n", &[]),
        "parameters.k = \"3 kN\": kN is a force, but this entry needs a stiffness (N/m)"
    );
    // A quantity does not hide the place of another problem.
    let text = "[initial]\nspeed = \"56 km/h\"\n\n[simulation]\ntend = 0.1\n";
    let e = Scenario::parse(text, Some(Path::new("s.toml")), &names, &[]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("s.toml:5:1: unknown field `tend`"),
        "{e}"
    );
    assert_eq!(
        error("", &["m=3 m"]),
        "--set m=\"3 m\": m is a length, but this entry needs a mass (kg)"
    );
    assert_eq!(
        error("[simulation]\nt_end = \"0.1\"\n", &[]),
        "simulation.t_end = \"0.1\": has no unit: write it in s, or as a number without quotes (SI)"
    );
}

#[test]
fn every_unit_a_component_section_declares_is_a_unit() {
    use crate::components::{ComponentSection, Measure};
    for kind in ComponentSection::KINDS {
        for (key, measure) in ComponentSection::units_of(kind).unwrap() {
            let units = match measure {
                Measure::One(unit) => vec![*unit],
                Measure::Pairs(a, b) => vec![*a, *b],
            };
            for unit in units {
                let value = crate::quantity::value_in(&format!("1 {unit}"), unit);
                assert_eq!(value, Ok(1.0), "{kind}.{key}: {unit}");
            }
        }
    }
}

/// A mass on a crush element: the contact of the `[iso_mme]` tests.
const ON_A_WALL: &str = "model OnAWall;\ncoordinates { x [m], }\nparameters { m [kg] = 1.0, }\ninputs { crush(x [m], v [m/s]) [N], }\nkinetic = 0.5 * m * pow(dot(x), 2);\npotential = 0.0;\nforce x = crush(x, dot(x));\n";

/// The crush element of [`ON_A_WALL`].
const WALL: &str = "[metrics]\ncrush = \"-x\"\n[components.wall]\ntype = \"crush\"\ninputs = { force = \"crush\" }\ncompression = \"negative\"\nforce_breakpoints = [0.1]\nforce_values = [1e3]\ndamping_breakpoints = [1.0]\ndamping_values = [0.0, 0.0]\n";

#[test]
fn an_iso_mme_code_that_is_not_one_is_located_with_its_key() {
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    let text = format!("{PUSH}\n[iso_mme.channels]\nx = \"10VEHCCG0000QQXP\"\n");
    let e = Scenario::parse(&text, Some(Path::new("s.toml")), &names, &[]).unwrap_err();
    assert_eq!(e.key, Some(KeyPath::new("iso_mme.channels.x")));
    assert_eq!(
        e.to_string(),
        "s.toml:6:5: iso_mme.channels.x = \"10VEHCCG0000QQXP\": channel code \"10VEHCCG0000QQXP\": \
         the physical dimension (position 13) is \"QQ\"; expected a physical dimension of RED B \
         (AC, VE, DS, DC, FO, MO, EN, AN, AV, AA, …, 00, or 1x/2x lab- or customer-specific)"
    );
    // A short code, a column the model does not have, a code given twice.
    let e = error(
        &format!("{PUSH}[iso_mme.channels]\nx = \"10VEHCCG\"\n"),
        &[],
    );
    assert!(e.contains("has 8 characters; a channel code has 16"), "{e}");
    let e = error(
        &format!("{PUSH}[iso_mme.channels]\ny = \"10VEHCCG0000DSXP\"\n"),
        &[],
    );
    assert!(e.starts_with("iso_mme.channels.y"), "{e}");
    let twice = format!(
        "{PUSH}[iso_mme.channels]\nx = \"10VEHCCG0000DSXP\"\nx_dot = \"10VEHCCG0000DSXP\"\n"
    );
    let e = error(&twice, &[]);
    assert!(e.contains("the code is given to `x` already"), "{e}");
    let e = error(&format!("{PUSH}[iso_mme]\nname = \"a/b\"\n"), &[]);
    assert!(e.starts_with("iso_mme.name = \"a/b\""), "{e}");
    let e = error(&format!("{PUSH}[iso_mme]\ncodes = 1\n"), &[]);
    assert!(e.contains("unknown field `codes`"), "{e}");
}

#[test]
fn an_iso_mme_section_resolves_its_channels_and_barrier_force() {
    let spring = ModelNames::of_interpreted(&lagrangian_core::interpret(SPRING).unwrap());
    // No section: no channels, no barrier without a contact element.
    let none = Scenario::parse(PUSH, None, &spring, &[]).unwrap().iso_mme;
    assert_eq!(none, iso_mme::IsoMme::default());
    let names = ModelNames::of_interpreted(&lagrangian_core::interpret(ON_A_WALL).unwrap());
    let parse = |text: &str| Scenario::parse(text, None, &names, &[]).unwrap().iso_mme;
    // The one crush component is the barrier's load by default.
    let with_wall = parse(WALL);
    assert_eq!(with_wall.barrier_force.unwrap().name, "wall.force");
    let text = format!(
        "{WALL}[iso_mme]\ntitle = \"T\"\nlaboratory = \"L\"\nbarrier_force = \"\"\n[iso_mme.channels]\n\"x_ddot\" = \"11CHST0000H3ACXA\"\n\"wall.deflection\" = \"10VEHC000000DCXP\"\n"
    );
    let section = parse(&text);
    assert_eq!(
        (section.title.as_deref(), section.laboratory.as_deref()),
        (Some("T"), Some("L"))
    );
    assert_eq!(section.barrier_force, None);
    let channels: Vec<(&str, &str)> = (section.channels.iter())
        .map(|c| (c.signal.name.as_str(), c.code.as_str()))
        .collect();
    assert_eq!(
        channels,
        [
            ("wall.deflection", "10VEHC000000DCXP"),
            ("x_ddot", "11CHST0000H3ACXA")
        ]
    );
    // A --set reaches the section too.
    let set = Override::parse_all(&["iso_mme.channels.x=\"10VEHCCG0000DSXW\""]).unwrap();
    let e = Scenario::parse(WALL, None, &names, &set).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("--set iso_mme.channels.x=\"10VEHCCG0000DSXW\""),
        "{e}"
    );
}
