//! Settings read from the environment (`RT_BACKEND`, `RT_TRAVERSAL`,
//! `RT_CPU_SIMD`): one rule for all of them, that a variable set to
//! nothing (`RT_TRAVERSAL=`, or only blanks) is unset, as a shell user
//! means it, and that its value is read without surrounding blanks.

/// The value of the environment variable `name`, trimmed; `None` when it is
/// unset, empty or blank (or not Unicode, which no setting's value is).
pub(crate) fn setting(name: &str) -> Option<String> {
    let v = std::env::var(name).ok()?;
    let v = v.trim();
    (!v.is_empty()).then(|| v.to_string())
}

#[cfg(test)]
mod tests {
    use super::setting;

    #[test]
    fn empty_and_blank_values_are_unset_and_values_are_trimmed() {
        // Names no other test reads; set before any thread of this test
        // reads the environment.
        unsafe {
            std::env::set_var("RT_TEST_SETTING_EMPTY", "");
            std::env::set_var("RT_TEST_SETTING_BLANK", "  \t");
            std::env::set_var("RT_TEST_SETTING_VALUE", " compute ");
        }
        assert_eq!(setting("RT_TEST_SETTING_EMPTY"), None);
        assert_eq!(setting("RT_TEST_SETTING_BLANK"), None);
        assert_eq!(setting("RT_TEST_SETTING_UNSET_EVER"), None);
        assert_eq!(setting("RT_TEST_SETTING_VALUE").as_deref(), Some("compute"));
    }
}
