//! The library's progress hooks (issue 16, item 5): `diagnostics::report_with_progress`,
//! `lut::bake_with_progress`, `lut::lookup_error_with_progress` and
//! `fit::all_fits_with_progress` call their `progress(done, total)` with `done` never
//! decreasing, one `total`, and last `(total, total)`; and they compute what the functions
//! without the hook compute.

use hairmath::diagnostics::{
    report, report_steps, report_with_progress, ReportDetail, ReportSettings,
};
use hairmath::lut::{
    bake, bake_with_progress, lookup_error, lookup_error_with_progress, NguyenM, NguyenN,
};
use hairmath::params::RefractiveIndex;
use std::sync::Mutex;

/// The calls a progress hook received.
#[derive(Default)]
struct Calls(Mutex<Vec<(usize, usize)>>);

impl Calls {
    /// The hook that records its calls.
    fn hook(&self) -> impl Fn(usize, usize) + Sync + '_ {
        move |done, total| self.0.lock().unwrap().push((done, total))
    }

    /// The recorded calls, checked: at least one, every `total` equal to `total`, `done`
    /// non-decreasing and at most `total`, the last call `(total, total)`.
    fn checked(&self, total: usize) -> Vec<(usize, usize)> {
        let calls = self.0.lock().unwrap().clone();
        assert!(!calls.is_empty(), "no progress reported");
        assert!(calls.iter().all(|&(_, t)| t == total), "{calls:?}");
        assert!(calls.windows(2).all(|w| w[0].0 <= w[1].0), "{calls:?}");
        assert!(calls.iter().all(|&(d, _)| d <= total), "{calls:?}");
        assert_eq!(calls.last(), Some(&(total, total)), "{calls:?}");
        calls
    }

    /// No call was recorded.
    fn none(&self) -> bool {
        self.0.lock().unwrap().is_empty()
    }
}

#[test]
fn report_reports_every_step_and_computes_the_same_figures() {
    let settings = ReportSettings::new(ReportDetail::Quick);
    let calls = Calls::default();
    let with = report_with_progress(&settings, &calls.hook()).unwrap();
    let total = report_steps(&settings);
    // One call per step, counting up by one.
    let expected: Vec<(usize, usize)> = (1..=total).map(|d| (d, total)).collect();
    assert_eq!(calls.checked(total), expected);
    let without = report(&settings).unwrap();
    // Everything but the wall-clock timings (the timing section and the integrator's costs).
    assert_eq!(with.hairs, without.hairs);
    assert_eq!(with.convergence, without.convergence);
    assert_eq!(with.furnace, without.furnace);
    for (a, b) in with.integrator.rows.iter().zip(&without.integrator.rows) {
        assert_eq!(
            (a.beta_n, &a.errors, a.reference_refinement),
            (b.beta_n, &b.errors, b.reference_refinement)
        );
    }
    assert_eq!(with.integrator.rows.len(), without.integrator.rows.len());
}

#[test]
fn lut_bake_reports_its_samples_and_bakes_the_same_table() {
    let baker = NguyenM::default();
    // 4096 samples: at most about a thousand calls, at equal steps.
    let calls = Calls::default();
    let table = bake_with_progress(&baker, &[64, 64], &calls.hook()).unwrap();
    let seen = calls.checked(4096);
    assert!((500..=1001).contains(&seen.len()), "{} calls", seen.len());
    assert_eq!(table, bake(&baker, &[64, 64]).unwrap());
    // Fewer samples than reports: one call per sample.
    let calls = Calls::default();
    bake_with_progress(&baker, &[3, 2], &calls.hook()).unwrap();
    let expected: Vec<(usize, usize)> = (1..=6).map(|d| (d, 6)).collect();
    assert_eq!(calls.checked(6), expected);
    // Refused sizes: an error and no progress.
    let calls = Calls::default();
    assert!(bake_with_progress(&baker, &[64], &calls.hook()).is_err());
    assert!(calls.none());
}

#[test]
fn lookup_error_reports_its_points_and_measures_the_same() {
    let baker = NguyenN::new(
        RefractiveIndex::new(1.55).unwrap(),
        hairmath::absorption::Absorption::new([0.2, 0.4, 0.8]).unwrap(),
        None,
    );
    let table = bake(&baker, &[16, 16]).unwrap();
    for points in [1, 999, 2500] {
        let calls = Calls::default();
        let with = lookup_error_with_progress(&baker, &table, points, &calls.hook()).unwrap();
        calls.checked(points);
        assert_eq!(with, lookup_error(&baker, &table, points).unwrap());
    }
    let calls = Calls::default();
    lookup_error_with_progress(&baker, &table, 0, &calls.hook()).unwrap();
    assert!(calls.none(), "no points, no progress");
}

#[cfg(feature = "fit")]
#[test]
fn all_fits_reports_each_family_and_fits_the_committed_constants() {
    use hairmath::fit::{all_fits_with_progress, constants_source, FitSettings, FIT_FAMILIES};
    let settings = FitSettings::default();
    let calls = Calls::default();
    let fits = all_fits_with_progress(&settings, &calls.hook()).unwrap();
    let expected: Vec<(usize, usize)> = (1..=FIT_FAMILIES).map(|d| (d, FIT_FAMILIES)).collect();
    assert_eq!(calls.checked(FIT_FAMILIES), expected);
    // The same constants as `all_fits` (tests/fit_constants.rs checks those are committed).
    assert_eq!(
        constants_source(&settings, &fits),
        include_str!("../src/models/constants.rs")
    );
}
