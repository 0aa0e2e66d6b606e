//! The loaders' panic boundary: a panic while loading (a bug, here or in a
//! format crate, that a file triggered) becomes [`SceneError::Internal`]
//! naming the file and where it panicked, and the process's panic hook
//! stays silent for it, so the error is the one line a user sees.
//!
//! The hook is installed once, over whatever hook the process had, and
//! passes every panic outside a load (or on another thread) to that hook
//! unchanged.

use crate::SceneError;
use std::cell::{Cell, RefCell};
use std::panic::{self, AssertUnwindSafe};
use std::path::Path;
use std::sync::Once;

thread_local! {
    /// Loads running on this thread (a load may start another).
    static LOADING: Cell<u32> = const { Cell::new(0) };
    /// Where the last panic inside a load happened, `file:line`.
    static WHERE: RefCell<Option<String>> = const { RefCell::new(None) };
}

static QUIET_HOOK: Once = Once::new();

/// `load` run with its panics caught as [`SceneError::Internal`] naming
/// `path`.
pub(crate) fn guarded<T>(path: &Path, load: impl FnOnce() -> Result<T, SceneError>) -> Result<T, SceneError> {
    install_quiet_hook();
    LOADING.with(|n| n.set(n.get() + 1));
    let result = panic::catch_unwind(AssertUnwindSafe(load));
    LOADING.with(|n| n.set(n.get() - 1));
    result.unwrap_or_else(|payload| {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic without a message".into());
        let first = text.lines().next().unwrap_or_default().to_string();
        let message = match WHERE.with(|w| w.borrow_mut().take()) {
            Some(at) => format!("{first} (at {at})"),
            None => first,
        };
        Err(SceneError::Internal { file: path.display().to_string(), message })
    })
}

/// Puts a hook in front of the process's: silent for panics inside a load
/// on the panicking thread (it only notes where), the previous hook's
/// output for every other panic.
fn install_quiet_hook() {
    QUIET_HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if LOADING.with(Cell::get) > 0 {
                let at = info.location().map(|l| format!("{}:{}", l.file(), l.line()));
                WHERE.with(|w| *w.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_while_loading_is_one_line_naming_the_file_and_where() {
        let e = guarded::<()>(Path::new("x.glb"), || panic!("boom\nsecond line")).unwrap_err();
        let line = e.to_string();
        assert!(line.starts_with("x.glb: internal error while loading (a bug; please report it): boom (at "), "{line}");
        assert!(line.contains("guard.rs:"), "{line}");
        assert!(!line.contains('\n'), "{line}");
        assert!(e.is_bad_input());
    }

    #[test]
    fn the_boundary_is_left_when_the_load_returns() {
        assert!(guarded(Path::new("x.obj"), || Ok(1)).is_ok());
        let _ = guarded::<()>(Path::new("x.obj"), || panic!("inside"));
        assert_eq!(LOADING.with(Cell::get), 0);
        assert!(WHERE.with(|w| w.borrow().is_none()));
    }
}
