//! Helpers shared by the command-line tests that run the `hairmath` binary and read its JSON.

use serde_json::Value;
use std::process::Command;

/// Runs `hairmath` with `args` and returns its stdout (the command must succeed). Its stderr
/// is a pipe, not a terminal: it must carry no progress bar ([`assert_no_progress`]).
pub fn hairmath(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_hairmath"))
        .args(args)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "hairmath {args:?} failed: {stderr}");
    assert_no_progress(args, &stderr);
    String::from_utf8(o.stdout).expect("UTF-8 output")
}

/// `stderr`, written by `hairmath args` to a pipe, carries no trace of a progress bar: no
/// terminal escape codes, no carriage returns, nothing of the bars' template
/// (`msg [=====>    ] done/total, elapsed (eta ...)`).
pub fn assert_no_progress(args: &[&str], stderr: &str) {
    for mark in ["\x1b", "\r", "[=", "[>", "=>", "(eta "] {
        assert!(
            !stderr.contains(mark),
            "hairmath {args:?} drew a progress bar on a pipe ({mark:?}): {stderr:?}"
        );
    }
}

/// `value` as a number.
pub fn num(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("{value} is not a number"))
}

/// The JSON number `json` is `value`. serde_json prints the shortest representation that
/// round-trips, but its default parser (without the `float_roundtrip` feature) may round the
/// last bit, so equality is to 2 ulps.
pub fn same(json: &Value, value: f64) {
    let parsed = num(json);
    assert!(
        parsed == value || (parsed - value).abs() <= 4.5e-16 * value.abs(),
        "{parsed:e} (JSON) vs {value:e} (library)"
    );
}
