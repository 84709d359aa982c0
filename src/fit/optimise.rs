//! The optimisers every fit uses: argmin's Brent minimiser for one parameter, argmin's
//! Nelder-Mead simplex for several, nalgebra's SVD for linear least squares, and a check that
//! a returned point is a minimum.
//!
//! Each run reports argmin's termination reason; a run that stops for any reason other than
//! convergence is an error ([`FitError::NotConverged`]), never a silently returned value.

use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::brent::BrentOpt;
use argmin::solver::neldermead::NelderMead;

/// Why a fit failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FitError {
    /// The optimiser stopped without converging.
    #[error("fit of {what} did not converge: {reason}")]
    NotConverged {
        /// What was being fitted.
        what: String,
        /// argmin's termination reason, in words.
        reason: String,
    },
    /// The loss was not finite at the optimum, or the problem was degenerate.
    #[error("fit of {what} failed: {reason}")]
    Degenerate {
        /// What was being fitted.
        what: String,
        /// What went wrong.
        reason: String,
    },
    /// An invalid fit setting (for example a refractive index <= 1).
    #[error(transparent)]
    Param(#[from] crate::error::ParamError),
}

/// The result of one optimiser run.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    /// The parameters at the minimum.
    pub params: Vec<f64>,
    /// The loss there.
    pub loss: f64,
    /// Iterations the optimiser took.
    pub iterations: u64,
    /// argmin's termination reason, in words (always a convergence reason: other outcomes are
    /// [`FitError::NotConverged`]).
    pub termination: String,
}

/// Iteration cap of every run; convergence takes well under a tenth of it in every fit here.
const MAX_ITERATIONS: u64 = 20_000;

struct Scalar<F>(F);

impl<F: Fn(f64) -> f64> CostFunction for Scalar<F> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &f64) -> Result<f64, argmin::core::Error> {
        Ok((self.0)(*x))
    }
}

struct Vector<F>(F);

impl<F: Fn(&[f64]) -> f64> CostFunction for Vector<F> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        Ok((self.0)(x))
    }
}

/// argmin's own failures (an invalid solver setting, a panicking loss) as [`FitError::Degenerate`].
fn argmin_failure(what: &str) -> impl Fn(argmin::core::Error) -> FitError + '_ {
    move |e| FitError::Degenerate {
        what: what.into(),
        reason: e.to_string(),
    }
}

fn converged(
    what: &str,
    status: &TerminationStatus,
    iterations: u64,
    params: Vec<f64>,
    loss: f64,
) -> Result<Minimum, FitError> {
    let reason = match status {
        TerminationStatus::Terminated(reason) => reason,
        TerminationStatus::NotTerminated => {
            return Err(FitError::NotConverged {
                what: what.into(),
                reason: "the optimiser did not terminate".into(),
            })
        }
    };
    if *reason != TerminationReason::SolverConverged {
        return Err(FitError::NotConverged {
            what: what.into(),
            reason: reason.text().into(),
        });
    }
    if !loss.is_finite() || params.iter().any(|p| !p.is_finite()) {
        return Err(FitError::Degenerate {
            what: what.into(),
            reason: format!("non-finite result: params {params:?}, loss {loss}"),
        });
    }
    Ok(Minimum {
        params,
        loss,
        iterations,
        termination: reason.text().into(),
    })
}

/// Minimises `loss` over `[lo, hi]` with Brent's method (argmin `BrentOpt`), to an absolute
/// parameter tolerance `tol` (plus 1.5e-8 relative, Brent's floor).
///
/// # Errors
/// [`FitError::NotConverged`] if argmin stops for any reason but convergence;
/// [`FitError::Degenerate`] for a non-finite loss at the minimum.
pub fn minimize_scalar(
    what: &str,
    loss: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    tol: f64,
) -> Result<Minimum, FitError> {
    let solver = BrentOpt::new(lo, hi).set_tolerance(1.5e-8, tol);
    let result = Executor::new(Scalar(loss), solver)
        .configure(|state| state.max_iters(MAX_ITERATIONS))
        .run()
        .map_err(argmin_failure(what))?;
    let state = result.state();
    let best = state.get_best_param().copied().unwrap_or(f64::NAN);
    converged(
        what,
        state.get_termination_status(),
        state.get_iter(),
        vec![best],
        state.get_best_cost(),
    )
}

/// Minimises `loss` with the Nelder-Mead simplex (argmin `NelderMead`), starting from the
/// simplex `start`, `start + step_i e_i`, until the standard deviation of the simplex's losses
/// falls below `loss_tol`.
///
/// # Errors
/// As [`minimize_scalar`].
pub fn minimize(
    what: &str,
    loss: impl Fn(&[f64]) -> f64,
    start: &[f64],
    step: &[f64],
    loss_tol: f64,
) -> Result<Minimum, FitError> {
    let mut simplex = vec![start.to_vec()];
    for (i, s) in step.iter().enumerate() {
        let mut vertex = start.to_vec();
        vertex[i] += s;
        simplex.push(vertex);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(loss_tol)
        .map_err(argmin_failure(what))?;
    let result = Executor::new(Vector(loss), solver)
        .configure(|state| state.max_iters(MAX_ITERATIONS))
        .run()
        .map_err(argmin_failure(what))?;
    let state = result.state();
    let best = state.get_best_param().cloned().unwrap_or_default();
    converged(
        what,
        state.get_termination_status(),
        state.get_iter(),
        best,
        state.get_best_cost(),
    )
}

/// Least-squares solution `x` of `sum_k (rows_k . x - targets_k)^2 -> min` by nalgebra's SVD.
///
/// # Errors
/// [`FitError::Degenerate`] when the rows do not determine `x` (rank deficient) or have
/// different lengths.
pub fn linear_least_squares(
    what: &str,
    rows: &[Vec<f64>],
    targets: &[f64],
) -> Result<Vec<f64>, FitError> {
    let degenerate = |reason: String| FitError::Degenerate {
        what: what.into(),
        reason,
    };
    let columns = rows.first().map_or(0, Vec::len);
    if columns == 0 || rows.len() != targets.len() || rows.iter().any(|r| r.len() != columns) {
        return Err(degenerate(format!(
            "{} rows of unequal or zero length for {} targets",
            rows.len(),
            targets.len()
        )));
    }
    let a = nalgebra::DMatrix::from_fn(rows.len(), columns, |i, j| rows[i][j]);
    let b = nalgebra::DVector::from_column_slice(targets);
    let svd = a.svd(true, true);
    let largest = svd.singular_values.max();
    if svd.rank(largest * 1e-12) < columns {
        return Err(degenerate("the design matrix is rank deficient".into()));
    }
    let x = svd
        .solve(&b, largest * 1e-12)
        .map_err(|e| degenerate(e.into()))?;
    Ok(x.iter().copied().collect())
}

/// Whether `params` is a strict local minimum of `loss` along each coordinate: moving any one
/// parameter by `relative_step` of its magnitude (or by `relative_step` if it is zero) in either
/// direction increases the loss.
pub fn is_coordinate_minimum(
    loss: impl Fn(&[f64]) -> f64,
    params: &[f64],
    relative_step: f64,
) -> bool {
    let at = loss(params);
    (0..params.len()).all(|i| {
        let step = relative_step * params[i].abs().max(1.0e-3);
        [-step, step].iter().all(|d| {
            let mut moved = params.to_vec();
            moved[i] += d;
            loss(&moved) > at
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_a_known_minimum_and_reports_convergence() {
        let m = minimize_scalar("parabola", |x| (x - 0.3).powi(2) + 1.0, -1.0, 1.0, 1e-10).unwrap();
        assert!((m.params[0] - 0.3).abs() < 1e-8, "{m:?}");
        assert_eq!(m.termination, TerminationReason::SolverConverged.text());
    }

    #[test]
    fn nelder_mead_recovers_rosenbrock() {
        let rosen = |p: &[f64]| (1.0 - p[0]).powi(2) + 100.0 * (p[1] - p[0] * p[0]).powi(2);
        let m = minimize("rosenbrock", rosen, &[-1.2, 1.0], &[0.1, 0.1], 1e-16).unwrap();
        assert!(
            (m.params[0] - 1.0).abs() < 1e-4 && (m.params[1] - 1.0).abs() < 1e-4,
            "{m:?}"
        );
        assert!(is_coordinate_minimum(rosen, &m.params, 1e-3));
        assert!(!is_coordinate_minimum(rosen, &[0.5, 0.5], 1e-3));
    }

    #[test]
    fn too_few_iterations_is_an_error_not_a_value() {
        // A loss that never settles: Nelder-Mead runs into the iteration cap.
        let err = minimize("unbounded", |p| -p[0].abs(), &[1.0], &[1.0], 0.0).unwrap_err();
        assert!(matches!(
            err,
            FitError::NotConverged { .. } | FitError::Degenerate { .. }
        ));
    }

    #[test]
    fn linear_least_squares_recovers_a_line_and_rejects_rank_deficiency() {
        let rows: Vec<Vec<f64>> = (0..10).map(|i| vec![1.0, i as f64]).collect();
        let targets: Vec<f64> = (0..10).map(|i| 2.0 - 0.5 * i as f64).collect();
        let x = linear_least_squares("line", &rows, &targets).unwrap();
        assert!(
            (x[0] - 2.0).abs() < 1e-12 && (x[1] + 0.5).abs() < 1e-12,
            "{x:?}"
        );
        let flat: Vec<Vec<f64>> = (0..10).map(|_| vec![1.0, 2.0]).collect();
        assert!(linear_least_squares("flat", &flat, &targets).is_err());
    }
}
