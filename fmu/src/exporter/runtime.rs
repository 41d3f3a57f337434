//! The check of an FMU binary before it is packed: a shared library (ELF,
//! Mach-O or PE, of the kind a host loads) for the platform the FMU's
//! `binaries/<platform>` folder names, whose dynamic symbol table exports
//! every FMI 2.0 function ([`crate::export::FMI2_FUNCTIONS`]). So
//! `--runtime /etc/passwd`, a library of another platform, or the Python
//! extension (which exports none) is refused before anything is written.

use crate::export::FMI2_FUNCTIONS;
use lagrangian_studies::error::StudyError;
use object::{Architecture, BinaryFormat, Object, ObjectKind};
use std::path::Path;

/// The binary format and architecture of this platform's libraries.
fn expected() -> (BinaryFormat, Architecture) {
    let format = match std::env::consts::OS {
        "windows" => BinaryFormat::Pe,
        "macos" | "ios" => BinaryFormat::MachO,
        _ => BinaryFormat::Elf,
    };
    let architecture = match std::env::consts::ARCH {
        "x86_64" => Architecture::X86_64,
        "aarch64" => Architecture::Aarch64,
        "x86" => Architecture::I386,
        _ => Architecture::Unknown,
    };
    (format, architecture)
}

/// `Ok` if `bytes` (the file `path`, named by `whence`: `--runtime`, …) is
/// a shared library of this platform that exports every FMI 2.0 function.
pub fn check(path: &Path, whence: &str, bytes: &[u8]) -> Result<(), StudyError> {
    let refuse = |why: String| {
        StudyError::usage(format!(
            "the FMU runtime {} ({whence}) {why}: name the lagrangian-fmu library ({}, built by \
             `cargo build -p lagrangian-fmu`) with --runtime PATH or {}",
            path.display(),
            library_file(),
            super::RUNTIME_VARIABLE
        ))
    };
    let file = object::File::parse(bytes).map_err(|_| {
        refuse(format!(
            "is not a shared library (no ELF, Mach-O or PE header: {})",
            first_bytes(bytes)
        ))
    })?;
    let (format, architecture) = expected();
    if (file.format(), file.architecture()) != (format, architecture) {
        return Err(refuse(format!(
            "is a {:?} file for {:?}, and this platform's libraries are {format:?} for \
             {architecture:?}",
            file.format(),
            file.architecture()
        )));
    }
    if file.kind() != ObjectKind::Dynamic {
        return Err(refuse(format!(
            "is a {:?} file, not a shared library",
            file.kind()
        )));
    }
    let missing = missing_functions(&file);
    match missing.len() {
        0 => Ok(()),
        n if n == FMI2_FUNCTIONS.len() => Err(refuse(format!(
            "exports none of the {n} FMI 2.0 functions (no fmi2Instantiate): it is not an FMU binary"
        ))),
        n => Err(refuse(format!(
            "exports {} of the {} FMI 2.0 functions (missing: {}): it is not a complete FMU binary",
            FMI2_FUNCTIONS.len() - n,
            FMI2_FUNCTIONS.len(),
            listed(&missing)
        ))),
    }
}

/// The first few `names`, then how many more.
fn listed(names: &[&str]) -> String {
    match names.len() {
        0..=4 => names.join(", "),
        n => format!("{} and {} more", names[..3].join(", "), n - 3),
    }
}

/// The FMI 2.0 functions `file`'s dynamic symbol table does not export.
fn missing_functions(file: &object::File) -> Vec<&'static str> {
    let exports = file.exports().unwrap_or_default();
    let names: std::collections::HashSet<&[u8]> = (exports.iter())
        .map(|e| e.name())
        // Mach-O names C symbols with a leading underscore.
        .map(|n| match file.format() {
            BinaryFormat::MachO => n.strip_prefix(b"_").unwrap_or(n),
            _ => n,
        })
        .collect();
    (FMI2_FUNCTIONS.iter().copied())
        .filter(|f| !names.contains(f.as_bytes()))
        .collect()
}

/// The runtime's file name on this platform (`liblagrangian_fmu.so`).
pub fn library_file() -> String {
    format!(
        "{}{}{}",
        std::env::consts::DLL_PREFIX,
        super::MODEL_IDENTIFIER,
        std::env::consts::DLL_SUFFIX
    )
}

/// The first bytes of a file, in hex, for a message.
fn first_bytes(bytes: &[u8]) -> String {
    match bytes.is_empty() {
        true => "it is empty".to_string(),
        false => {
            let hex: Vec<String> = bytes.iter().take(4).map(|b| format!("{b:02x}")).collect();
            format!("it starts with the bytes {}", hex.join(" "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(bytes: &[u8]) -> String {
        let Err(failure) = check(Path::new("x.so"), "--runtime", bytes) else {
            panic!("accepted");
        };
        failure.to_string()
    }

    #[test]
    fn a_partial_list_of_missing_functions_is_short() {
        assert_eq!(listed(&["a", "b"]), "a, b");
        assert_eq!(listed(&["a", "b", "c", "d", "e"]), "a, b, c and 2 more");
    }

    #[test]
    fn text_and_empty_files_are_no_shared_libraries() {
        let text = message(b"root:x:0:0:root:/root:/bin/bash\n");
        assert!(text.contains("is not a shared library"), "{text}");
        assert!(text.contains("the bytes 72 6f 6f 74"), "{text}");
        assert!(message(b"").contains("header: it is empty)"));
    }

    #[test]
    fn the_executable_running_the_test_is_not_a_shared_library_with_fmi_functions() {
        let exe = std::fs::read(std::env::current_exe().unwrap()).unwrap();
        let text = message(&exe);
        // A PIE executable is ET_DYN, like a library: its exports decide.
        assert!(
            text.contains("not a shared library") || text.contains("exports none of the 44"),
            "{text}"
        );
    }
}
