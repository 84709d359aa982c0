//! The scene files of `hairmath plan` ([`hairmath::plan::Scene::parse`]) on arbitrary text: no
//! panic, and an error names a line of the text.
#![no_main]

use hairmath::plan::Scene;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Err(e) = Scene::parse(text, "fuzz.toml") {
        assert!(e.line >= 1 && e.line <= text.lines().count().max(1) + 1, "{e}");
    }
});
