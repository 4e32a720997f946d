//! The one place where errors of the library crates are put in the terms of
//! the command line: the flag the user typed, the file, the element, and
//! what to do. Library messages stay as they are for Rust users; this layer
//! adds or replaces wording only where a library message names a Rust item
//! or an option the command line does not have.

use mesh_io::IoError;

use crate::output::CliError;

/// A mesh-io error in command-line terms.
pub fn io(e: IoError) -> CliError {
    match &e {
        IoError::Precision { .. } => format!("{e} (pass --allow-precision-loss to write it anyway)").into(),
        _ => e.into(),
    }
}

/// A number as a user would type it: plain for ordinary magnitudes,
/// scientific (`1e300`) otherwise.
pub fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        x.to_string()
    } else {
        format!("{x:e}")
    }
}
