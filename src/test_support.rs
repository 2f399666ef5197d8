//! What the library's own unit tests share.

/// A proptest configuration of `cases` cases that keeps the failures it
/// finds in `file` (under `tests/proptest-regressions/`, with the
/// integration tests' and beside the named regression tests), where every
/// later run tries them first.
pub(crate) fn proptest_config(cases: u32, file: &'static str) -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct(file),
        )),
        ..proptest::test_runner::Config::with_cases(cases)
    }
}
