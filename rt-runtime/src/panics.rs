//! Panics inside a launch, caught at its boundary.
//!
//! A panic in a program on the CPU backend (a user's `unwrap`, a slice
//! index, an assertion) or in the runtime itself must not unwind out of
//! `Context::launch` through a rayon worker: it becomes an [`RtError`]
//! naming the program, its file and line, the launch index and the message,
//! and the context stays usable. While a launch catches, the process's panic
//! hook records the message and the place instead of printing them (other
//! threads' panics, and panics outside launches, reach the hook installed
//! before, as always).
//!
//! [`RtError`]: crate::RtError

use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

/// What a caught panic said, and where.
#[derive(Clone, Debug)]
pub(crate) struct Caught {
    pub message: String,
    /// `file:line:column` of the panic.
    pub at: String,
}

thread_local! {
    static CATCHING: Cell<bool> = const { Cell::new(false) };
    static CAUGHT: RefCell<Option<Caught>> = const { RefCell::new(None) };
}

fn install_hook() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !CATCHING.with(Cell::get) {
                return previous(info);
            }
            let message = if let Some(s) = info.payload().downcast_ref::<&str>() {
                s.to_string()
            } else if let Some(s) = info.payload().downcast_ref::<String>() {
                s.clone()
            } else {
                "a panic with a non-string payload".to_string()
            };
            let at = info.location().map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column())).unwrap_or_default();
            CAUGHT.with(|c| *c.borrow_mut() = Some(Caught { message, at }));
        }));
    });
}

/// Runs `f`, returning what it panicked with instead of unwinding.
pub(crate) fn catching<R>(f: impl FnOnce() -> R) -> Result<R, Caught> {
    install_hook();
    let outer = CATCHING.with(|c| c.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    CATCHING.with(|c| c.set(outer));
    result.map_err(|payload| {
        CAUGHT.with(|c| c.borrow_mut().take()).unwrap_or_else(|| Caught {
            message: payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic with a non-string payload".into()),
            at: String::new(),
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caught_panic_keeps_its_message_and_place() {
        let caught = catching(|| {
            let v: Vec<u32> = Vec::new();
            v[3]
        })
        .unwrap_err();
        assert!(caught.message.contains("index out of bounds"), "{}", caught.message);
        assert!(caught.at.starts_with("rt-runtime/src/panics.rs:"), "{}", caught.at);
        assert_eq!(catching(|| 5).unwrap(), 5);
        let nested = catching(|| catching(|| panic!("inner")).unwrap_err().message).unwrap();
        assert_eq!(nested, "inner");
    }
}
