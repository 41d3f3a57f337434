//! The generic FMU binary of `lpm export-fmu`: the FMI 2.0 entry points of
//! [`lagrangian_fmi`] with the interpreter's plant, which runs the spec and
//! scenario packed in the FMU's `resources/`, so that exporting a model
//! needs no compiler.

lagrangian_fmi::export_fmi2!(lagrangian_fmi::plant::plant);
