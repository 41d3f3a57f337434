//! Crash test data in and out: ISO-MME (ISO/TS 13499) tests read from a
//! folder, an `.mme` or a `.zip` and written as a folder
//! ([`isomme::read`], [`isomme::write`]), their 16-character channel codes
//! checked field by field ([`ChannelCode`]), and NHTSA's EV5 ASCII tests
//! read ([`ev5::read`]).
//!
//! By phase: [`code`] is the channel code, [`text`] the `Name:value` line
//! files, `read` and `write` the ISO-MME test ([`isomme`]), [`ev5`] NHTSA's
//! format, [`error`] the errors, each naming the file, line and field.
//! pyisomme (MIT) is the reference the tests check both directions
//! against; facts come from it and the standards, code does not.

pub mod code;
pub mod error;
pub mod ev5;
mod read;
mod test;
pub mod text;
mod write;

pub use code::ChannelCode;
pub use error::{CodeError, ReadError, WriteError};

/// ISO-MME tests: the [`Test`](isomme::Test) held, read and written.
pub mod isomme {
    pub use crate::read::read;
    pub use crate::test::{Channel, Test};
    pub use crate::write::write;
}
