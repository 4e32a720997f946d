//! Panics as values: [`quietly`] swaps in a panic hook that records the
//! message and location instead of printing them, and [`catch`] turns a
//! panic of a closure into `Err(message)`. Used by the fuzzer and by the
//! dirty-mesh matrix, which must report panics, not die of them.

use std::panic::{self, AssertUnwindSafe};
use std::sync::Mutex;

/// The last panic's message and location.
static LAST: Mutex<Option<String>> = Mutex::new(None);

/// Runs `f` with the recording hook installed, then restores the previous
/// hook.
pub fn quietly<R>(f: impl FnOnce() -> R) -> R {
    let previous = panic::take_hook();
    panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| (*s).to_owned())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "(no message)".to_owned());
        let at = info.location().map(|l| format!(" at {}:{}", l.file(), l.line())).unwrap_or_default();
        if let Ok(mut last) = LAST.lock() {
            *last = Some(format!("{message}{at}"));
        }
    }));
    let out = f();
    panic::set_hook(previous);
    out
}

/// `Ok(f())`, or `Err(panic message)` if `f` panics (use inside
/// [`quietly`] to keep the message off the terminal).
pub fn catch<R>(f: impl FnOnce() -> R) -> Result<R, String> {
    panic::catch_unwind(AssertUnwindSafe(f)).map_err(|_| {
        LAST.lock().ok().and_then(|mut l| l.take()).unwrap_or_else(|| "panic (message not recorded)".to_owned())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_its_message() {
        let caught = quietly(|| catch(|| -> u32 { panic!("index {} out of range", 7) }));
        let message = caught.unwrap_err();
        assert!(message.starts_with("index 7 out of range at "), "{message}");
        assert_eq!(quietly(|| catch(|| 3)), Ok(3));
    }
}
