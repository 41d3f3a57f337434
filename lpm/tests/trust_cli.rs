//! What `lpm` tells a user about input it runs but does not trust: spec
//! warnings, sign sanity, tolerances and the energy balance.

mod common;

use common::{lpm, stderr, stdout, temporary};

#[test]
fn derive_prints_a_specs_warning_on_stderr_and_succeeds() {
    let dir = temporary("unit-warning");
    let spec = dir.join("partly.lpm");
    std::fs::write(
        &spec,
        "model Partly;\ncoordinates { x [m] }\nparameters { m [kg] = 1.0, k = 4.0 }\n\
         kinetic = 0.5 * m * pow(dot(x), 2);\npotential = 0.5 * k * pow(x, 2);\n",
    )
    .unwrap();
    let out = lpm(&["derive".as_ref(), spec.as_os_str()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.starts_with("warning: units are declared for some names but not for `k`: "),
        "{err}"
    );
    assert!(err.contains("partly.lpm:3:28"), "{err}");
    assert_eq!(err.matches("warning:").count(), 1, "{err}");
    assert!(stdout(&out).contains("M[x, x] = m"), "{}", stdout(&out));
}
