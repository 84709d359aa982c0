//! The committed constants file is what the fitter generates now (the full regeneration runs
//! in the normal test suite: a few seconds at the test profile's opt-level 3).

#![cfg(feature = "fit")]

use hairmath::fit::FitSettings;
use hairmath::fit::{all_fits, constants_source};

const COMMITTED: &str = include_str!("../src/models/constants.rs");

#[test]
fn committed_constants_are_up_to_date() {
    let settings = FitSettings::default();
    let fresh = constants_source(&settings, &all_fits(&settings).unwrap());
    if fresh != COMMITTED {
        let path = std::env::temp_dir().join("hairmath-constants.rs");
        std::fs::write(&path, &fresh).unwrap();
        let line = fresh
            .lines()
            .zip(COMMITTED.lines())
            .position(|(a, b)| a != b)
            .map_or(fresh.lines().count().min(COMMITTED.lines().count()), |i| i);
        panic!(
            "src/models/constants.rs is out of date (first difference at line {}); the fresh text \
             is in {}. Regenerate with `cargo run --release -- fit --write-constants \
             src/models/constants.rs`.",
            line + 1,
            path.display()
        );
    }
}

#[test]
fn every_record_has_a_finite_refit_and_error() {
    let fits = all_fits(&FitSettings::default()).unwrap();
    assert!(!fits.records.is_empty() && !fits.constants.is_empty());
    let mut keys = std::collections::BTreeSet::new();
    for r in &fits.records {
        assert!(keys.insert(r.key.clone()), "duplicate key {}", r.key);
        assert!(r.refit.is_finite() && r.refit_error.is_finite(), "{r:?}");
        assert!(
            r.published_error.is_some() == r.published.is_some(),
            "{r:?}"
        );
    }
    // Every generated constant documents itself.
    for c in &fits.constants {
        assert!(!c.doc.is_empty(), "{}", c.name);
    }
}
