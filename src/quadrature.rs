//! Deterministic quadrature for reference integrals (plain `f64`, not generic): composite
//! Gauss-Legendre rules on intervals, a product rule over the sphere of directions, adaptive
//! integration with an error estimate, and the crate's one deterministic point sequence
//! ([`kronecker`]) for test points and timing inputs.

use crate::error::ParamError;
use crate::geometry::{local_direction, V3};
use glam::DVec3;
use std::collections::BinaryHeap;

/// The largest `n` for which [`gauss_legendre`] runs Newton's method on the three-term
/// recurrence (O(n^2): 25 ms at n = 1000); above it the interior nodes come from Stieltjes'
/// asymptotic series (O(n)).
pub const NEWTON_MAX_NODES: usize = 1000;

/// Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1], nodes in decreasing order.
/// Exact for polynomials of degree 2n - 1.
///
/// For `n <= NEWTON_MAX_NODES` (1000) by Newton's method on the Legendre three-term recurrence
/// (Abramowitz and Stegun 25.4.29; initial guesses cos(pi (i - 1/4) / (n + 1/2))), O(n^2).
/// Above it in O(n) time, as Hale and Townsend 2013 ("Fast and accurate computation of
/// Gauss-Legendre and Gauss-Jacobi quadrature nodes and weights", SIAM J. Sci. Comput. 35)
/// do: Newton's method in theta on Stieltjes' asymptotic series of P_n(cos theta) (Szego,
/// "Orthogonal Polynomials", Theorem 8.21.5) for the nodes with `n sin(theta) >= 25`, and on
/// the recurrence for the few nodes nearer the ends; the rules agree with the recurrence's to
/// 2e-16 in the nodes and 1e-14 relative in the weights (tests). Cost: about 0.2 s per million
/// nodes and 16 bytes per node (the output); the only limit on `n` is the memory for the
/// output, as for any `Vec`.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    if n > NEWTON_MAX_NODES {
        return asymptotic_gauss_legendre(n);
    }
    (0..n)
        .map(|i| newton_node(n, initial_guess(n, i)))
        .collect()
}

/// The initial guess `cos(pi (i + 3/4) / (n + 1/2))` of node `i` (from the largest).
fn initial_guess(n: usize, i: usize) -> f64 {
    (core::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos()
}

/// Terms of Stieltjes' series [`gauss_legendre`] sums: at `n sin(theta) >= 25` the 20th term is
/// below 1e-16 of the first.
const STIELTJES_TERMS: usize = 20;
/// The smallest `n sin(theta)` at which [`gauss_legendre`] uses Stieltjes' series.
const STIELTJES_MIN_N_SIN: f64 = 25.0;

/// The n-point rule for large n in O(n) (see [`gauss_legendre`]): the nodes with `theta` in
/// (0, pi/2] (x >= 0) are computed and mirrored.
fn asymptotic_gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let series = Stieltjes::new(n);
    let half = n / 2;
    let mut positive = Vec::with_capacity(half);
    for i in 0..half {
        // Tricomi's initial guess (Hale and Townsend 2013, eq. 3.5 to first order).
        let t = core::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5);
        let mut theta = t + 1.0 / (8.0 * (n as f64 + 0.5).powi(2) * t.tan());
        let node = if n as f64 * theta.sin() >= STIELTJES_MIN_N_SIN {
            for _ in 0..10 {
                let (p, dp) = series.eval(theta);
                let step = p / dp;
                theta -= step;
                if step.abs() <= 1e-16 * theta {
                    break;
                }
            }
            let (_, dp) = series.eval(theta);
            (theta.cos(), 2.0 / (dp * dp))
        } else {
            newton_node(n, theta.cos())
        };
        positive.push(node);
    }
    let mut rule = positive.clone();
    if n % 2 == 1 {
        // The middle node x = 0 (theta = pi/2).
        let (_, dp) = series.eval(core::f64::consts::FRAC_PI_2);
        rule.push((0.0, 2.0 / (dp * dp)));
    }
    rule.extend(positive.iter().rev().map(|&(x, w)| (-x, w)));
    rule
}

/// A node of the n-point rule by Newton's method on the recurrence from the guess `x`, and its
/// weight.
fn newton_node(n: usize, mut x: f64) -> (f64, f64) {
    for _ in 0..100 {
        let (p, dp) = legendre_and_derivative(n, x);
        let step = p / dp;
        x -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    let (_, dp) = legendre_and_derivative(n, x);
    (x, 2.0 / ((1.0 - x * x) * dp * dp))
}

/// Stieltjes' series of P_n(cos theta) (Szego, Theorem 8.21.5):
/// `P_n(cos t) = C_n sum_m h_m cos(a_m) / (2 sin t)^(m + 1/2)` with
/// `a_m = (n + m + 1/2) t - (m + 1/2) pi / 2`, `h_0 = 1`,
/// `h_m = h_(m-1) (m - 1/2)^2 / (m (n + m + 1/2))` and
/// `C_n = (4 / pi) prod_(j=1..n) j / (j + 1/2) = (2 / sqrt(pi)) Gamma(n + 1) / Gamma(n + 3/2)`.
struct Stieltjes {
    n: f64,
    /// `C_n h_m`.
    coefficients: [f64; STIELTJES_TERMS],
}

impl Stieltjes {
    fn new(n: usize) -> Self {
        let nf = n as f64;
        let mut coefficients = [0.0; STIELTJES_TERMS];
        let mut c = 2.0 / core::f64::consts::PI.sqrt() * gamma_ratio(nf + 1.0);
        for (m, slot) in coefficients.iter_mut().enumerate() {
            if m > 0 {
                let mf = m as f64;
                c *= (mf - 0.5) * (mf - 0.5) / (mf * (nf + mf + 0.5));
            }
            *slot = c;
        }
        Stieltjes {
            n: nf,
            coefficients,
        }
    }

    /// `P_n(cos theta)` and its derivative in theta, for theta in (0, pi) with
    /// `n sin(theta) >= 25`.
    fn eval(&self, theta: f64) -> (f64, f64) {
        let (sin, cos) = theta.sin_cos();
        let inv_two_sin = 1.0 / (2.0 * sin);
        let mut power = inv_two_sin.sqrt();
        let (mut p, mut dp) = (0.0, 0.0);
        for (m, &c) in self.coefficients.iter().enumerate() {
            let k = m as f64 + 0.5;
            let a = (self.n + k) * theta - k * core::f64::consts::FRAC_PI_2;
            let (sin_a, cos_a) = a.sin_cos();
            p += c * cos_a * power;
            // d/dt [cos(a) (2 sin t)^-k] = -(n + k) sin(a) (2 sin t)^-k
            //                              - k cos(a) (2 sin t)^-k cos(t) / sin(t)
            dp -= c * power * ((self.n + k) * sin_a + k * cos_a * cos / sin);
            power *= inv_two_sin;
        }
        (p, dp)
    }
}

/// `Gamma(z) / Gamma(z + 1/2)` for `z >= 1000`, from Stirling's series of the log-gamma
/// difference (with Bernoulli polynomials, `B_(k+1)(1/2) - B_(k+1)(0) = (2^-k - 2) B_(k+1)`):
/// `ln(Gamma(z + 1/2) / Gamma(z)) = ln(z) / 2 - 1/(8 z) + 1/(192 z^3) - 1/(640 z^5)
/// + 17/(14336 z^7) - ...`; the next term is below 2e-30 at z = 1000.
fn gamma_ratio(z: f64) -> f64 {
    let inv = 1.0 / z;
    let inv2 = inv * inv;
    let tail =
        inv * (-1.0 / 8.0 + inv2 * (1.0 / 192.0 + inv2 * (-1.0 / 640.0 + inv2 * 17.0 / 14336.0)));
    (-(0.5 * z.ln() + tail)).exp()
}

/// P_n(x) and P_n'(x) by the recurrence (k + 1) P_{k+1} = (2k + 1) x P_k - k P_{k-1}.
fn legendre_and_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 1..n {
        let p2 = ((2 * k + 1) as f64 * x * p1 - k as f64 * p0) / (k + 1) as f64;
        p0 = p1;
        p1 = p2;
    }
    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// Integrates `f` over [a, b] with `panels` equal panels of the `rule`.
pub fn integrate(
    rule: &[(f64, f64)],
    panels: usize,
    a: f64,
    b: f64,
    mut f: impl FnMut(f64) -> f64,
) -> f64 {
    let width = (b - a) / panels as f64;
    let mut sum = 0.0;
    for k in 0..panels {
        let centre = a + (k as f64 + 0.5) * width;
        for &(x, w) in rule {
            sum += w * f(centre + 0.5 * width * x);
        }
    }
    0.5 * width * sum
}

/// Below this (in units of half the measure's extent) a recurrence coefficient of
/// [`gauss_rule_of_measure`] ends the rule: the measure has no more room for an orthogonal
/// polynomial than rounding leaves.
const RECURRENCE_FLOOR: f64 = 1e-13;

/// The Gauss rule of at most `n` nodes of a discrete measure, `points` `(x, w)` with `w >= 0`:
/// nodes and weights `(x, w)` in increasing x whose sum `sum w f(x)` equals the measure's
/// `sum_j w_j f(x_j)` for every polynomial f of degree below twice the node count.
///
/// It is how a rule is fitted to a weight function known only through a fine quadrature: the
/// fine rule's nodes cost little (the weight alone), the Gauss rule's few nodes carry the
/// expensive rest of the integrand. The recurrence of the measure's orthonormal polynomials
/// comes from Stieltjes' procedure on the discrete measure (Gautschi 2004, "Orthogonal
/// Polynomials: Computation and Approximation", section 2.2.3.1), in the variable mapped onto
/// [-1, 1] over the points of positive weight; the rule from the recurrence's Jacobi matrix
/// (Golub and Welsch 1969, "Calculation of Gauss quadrature rules", Math. Comp. 23): its
/// eigenvalues are the nodes ([`tridiagonal_eigenvalues`]), the squared first components of
/// its unit eigenvectors times the measure's mass the weights (computed as the Christoffel
/// numbers they equal, [`christoffel_weights`]). The node count is less than `n` where the
/// measure has fewer points of positive weight, or where a recurrence coefficient falls below
/// [`RECURRENCE_FLOOR`] (the polynomials' norms are then rounding); empty for an empty or
/// massless measure.
pub(crate) fn gauss_rule_of_measure(points: &[(f64, f64)], n: usize) -> Vec<(f64, f64)> {
    let live: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|&(x, w)| w > 0.0 && x.is_finite() && w.is_finite())
        .collect();
    let mass: f64 = live.iter().map(|p| p.1).sum();
    let n = n.min(live.len());
    if n == 0 || mass <= 0.0 {
        return Vec::new();
    }
    let (lo, hi) = live
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
    let (centre, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    if half <= 0.0 {
        return vec![(lo, mass)];
    }
    let t: Vec<f64> = live.iter().map(|p| (p.0 - centre) / half).collect();
    let (diagonal, off_diagonal) = stieltjes_recurrence(&live, &t, mass, n);
    let mut nodes = diagonal.clone();
    tridiagonal_eigenvalues(&mut nodes, &off_diagonal);
    let weights = christoffel_weights(&nodes, &diagonal, &off_diagonal);
    let mut rule: Vec<(f64, f64)> = nodes
        .iter()
        .zip(&weights)
        .map(|(&t, &w)| (centre + half * t, mass * w))
        .collect();
    rule.sort_by(|a, b| a.0.total_cmp(&b.0));
    rule
}

/// The Jacobi matrix of the discrete measure `(t_j, w_j)` (`points`' weights, `t` their
/// abscissae in [-1, 1]) for at most `n` nodes: its diagonal `alpha_k = <t p_k, p_k>` and its
/// off-diagonal `b_k = ||t p_{k-1} - alpha_{k-1} p_{k-1} - b_{k-1} p_{k-2}||` (k >= 1), with
/// `p_k` orthonormal (Stieltjes' procedure).
fn stieltjes_recurrence(
    points: &[(f64, f64)],
    t: &[f64],
    mass: f64,
    n: usize,
) -> (Vec<f64>, Vec<f64>) {
    // `current` holds p_k times `b_k` (p_{k-1} and the recurrence's new polynomial unscaled),
    // so that each step is one pass: it scales by `1 / b_k` as it reads, and sums the new
    // polynomial's norm and its first moment (`alpha_{k+1} b_{k+1}^2`) as it writes.
    let mut previous = vec![0.0; t.len()];
    let mut current = vec![1.0; t.len()];
    let alpha_0 = points.iter().zip(t).map(|(p, t)| p.1 * t).sum::<f64>() / mass;
    let (mut diagonal, mut off_diagonal) = (vec![alpha_0], Vec::with_capacity(n));
    let (mut b, mut scale) = (0.0, 1.0 / mass.sqrt());
    while diagonal.len() < n {
        let alpha = diagonal[diagonal.len() - 1];
        let (mut norm, mut moment) = (0.0, 0.0);
        for ((p, &t), (q, q_previous)) in points
            .iter()
            .zip(t)
            .zip(current.iter_mut().zip(previous.iter_mut()))
        {
            let q_scaled = *q * scale;
            let next = (t - alpha) * q_scaled - b * *q_previous;
            *q_previous = q_scaled;
            *q = next;
            let weighted = p.1 * next * next;
            norm += weighted;
            moment += weighted * t;
        }
        b = norm.sqrt();
        if b.is_nan() || b <= RECURRENCE_FLOOR {
            break;
        }
        scale = 1.0 / b;
        diagonal.push(moment / norm);
        off_diagonal.push(b);
    }
    off_diagonal.push(0.0);
    (diagonal, off_diagonal)
}

/// Most rational QL sweeps per eigenvalue of [`tridiagonal_eigenvalues`]; it takes two or
/// three.
const QL_SWEEPS: usize = 60;

/// Eigenvalues of the symmetric tridiagonal matrix with diagonal `d` and off-diagonal `e`
/// (`e[i]` joins rows i and i + 1; the last entry is unused), written over `d` in no
/// particular order: the rational QL algorithm of Pal, Walker and Kahan, which works on the
/// squares of the off-diagonal and takes no square root in the steps of a sweep (Reinsch
/// 1973, "Algorithm 464: eigenvalues of a real, symmetric, tridiagonal matrix", Comm. ACM 16;
/// EISPACK's `tqlrat`), with a Wilkinson shift. The crate's own, as nalgebra comes only with
/// the `fit` feature. The implicit QL with plane rotations that tracked the eigenvectors'
/// first row, which it replaces, spent a square root and a division in each rotation's chain
/// of dependent operations: in a `perf` profile of aligned far-field queries at beta_n 0.3 it
/// took 26% of the time, this one 19% (with the same two or three sweeps per eigenvalue), the
/// weights coming from [`christoffel_weights`].
fn tridiagonal_eigenvalues(d: &mut [f64], e: &[f64]) {
    let n = d.len();
    let mut e2: Vec<f64> = e.iter().map(|e| e * e).collect();
    e2[n - 1] = 0.0;
    let (mut shift_sum, mut largest) = (0.0_f64, 0.0_f64);
    let (mut floor, mut floor_squared) = (0.0, 0.0);
    for l in 0..n {
        let size = d[l].abs() + e2[l].sqrt();
        if size > largest {
            largest = size;
            floor = f64::EPSILON * largest;
            floor_squared = floor * floor;
        }
        let m = (l..n).find(|&m| e2[m] <= floor_squared).unwrap_or(n - 1);
        if m > l {
            for _ in 0..QL_SWEEPS {
                // The Wilkinson shift from the leading 2 x 2 block, taken out of the diagonal.
                let off = e2[l].sqrt();
                let g = d[l];
                let q = (d[l + 1] - g) / (2.0 * off);
                let r = (q * q + 1.0).sqrt();
                d[l] = off / (q + r.copysign(q));
                let shift = g - d[l];
                for value in &mut d[l + 1..n] {
                    *value -= shift;
                }
                shift_sum += shift;
                // One rational QL sweep from row m up to row l.
                let mut g = if d[m] == 0.0 { floor } else { d[m] };
                let (mut h, mut s) = (g, 0.0);
                for i in (l..m).rev() {
                    let p = g * h;
                    let r = p + e2[i];
                    e2[i + 1] = s * r;
                    s = e2[i] / r;
                    d[i + 1] = h + s * (h + d[i]);
                    g = d[i] - e2[i] / g;
                    if g == 0.0 {
                        g = floor;
                    }
                    h = g * (p / r);
                }
                e2[l] = s * g;
                d[l] = h;
                // Converged when the squared coupling `h e2[l]` is below the floor's square
                // (tested before the product, which could underflow).
                if h == 0.0 || e2[l].abs() <= (floor_squared / h).abs() {
                    break;
                }
                e2[l] *= h;
                if e2[l] == 0.0 {
                    break;
                }
            }
        }
        d[l] += shift_sum;
    }
}

/// The Gauss rule's weights at its nodes `t` for a measure of mass 1 with recurrence
/// coefficients `diagonal` and `off_diagonal` ([`stieltjes_recurrence`]): the Christoffel
/// numbers `1 / sum_k p_k(t)^2` over the orthonormal polynomials of degree below the node
/// count (Gautschi 2004), which equal the squared first components of the
/// Jacobi matrix's unit eigenvectors (Golub and Welsch 1969). Each node's sum is one pass of
/// the recurrence, independent of the others.
fn christoffel_weights(t: &[f64], diagonal: &[f64], off_diagonal: &[f64]) -> Vec<f64> {
    t.iter()
        .map(|&t| {
            // b_k p_k = (t - alpha_{k-1}) p_{k-1} - b_{k-1} p_{k-2}, from p_0 = 1, p_{-1} = 0.
            let (mut previous, mut current, mut sum, mut b_previous) = (0.0, 1.0, 1.0, 0.0);
            for (alpha, &b) in diagonal.iter().zip(off_diagonal).take(diagonal.len() - 1) {
                let next = ((t - alpha) * current - b_previous * previous) / b;
                (previous, current, b_previous) = (current, next, b);
                sum += current * current;
            }
            1.0 / sum
        })
        .collect()
}

/// The most directions of [`SphereRule::fibonacci`].
pub const MAX_FIBONACCI_DIRECTIONS: usize = 1 << 22;

/// `n` directions of the spherical Fibonacci set: `z_k = 1 - (2k + 1) / n`, azimuth `k` times
/// the golden angle `pi (3 - sqrt 5)`; each stands for the solid angle `4 pi / n`.
pub fn fibonacci_directions(n: usize) -> Vec<DVec3> {
    let golden_angle = core::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f64 / n as f64;
            let s = (1.0 - z * z).max(0.0).sqrt();
            let (sin, cos) = (golden_angle * k as f64).sin_cos();
            DVec3::new(s * cos, s * sin, z)
        })
        .collect()
}

/// A product rule over the unit sphere in the fibre's local frame (tangent +X):
/// composite Gauss-Legendre in theta in [-pi/2, pi/2] with weight cos(theta), and the midpoint
/// rule with `azimuths` nodes in phi, which converges geometrically for smooth periodic
/// integrands.
#[derive(Clone, Debug)]
pub struct SphereRule {
    /// (direction, weight) pairs; weights sum to 4 pi.
    pub nodes: Vec<(V3<f64>, f64)>,
}

impl SphereRule {
    /// `theta_panels` panels of an `order`-point rule in theta, `azimuths` nodes in phi.
    pub fn new(theta_panels: usize, order: usize, azimuths: usize) -> Self {
        let rule = gauss_legendre(order);
        let half_pi = core::f64::consts::FRAC_PI_2;
        let width = 2.0 * half_pi / theta_panels as f64;
        let dphi = 2.0 * core::f64::consts::PI / azimuths as f64;
        let mut nodes = Vec::with_capacity(theta_panels * order * azimuths);
        for k in 0..theta_panels {
            let centre = -half_pi + (k as f64 + 0.5) * width;
            for &(x, w) in &rule {
                let theta = centre + 0.5 * width * x;
                let wt = 0.5 * width * w * theta.cos() * dphi;
                for j in 0..azimuths {
                    let phi = -core::f64::consts::PI + (j as f64 + 0.5) * dphi;
                    nodes.push((local_direction(theta.sin(), theta.cos(), phi), wt));
                }
            }
        }
        SphereRule { nodes }
    }

    /// The equal-weight rule on the `n` directions of [`fibonacci_directions`] (each weighing
    /// `4 pi / n`): for integrands with discontinuities (a transmittance), where no product rule
    /// is exact, it spreads the error evenly over the sphere.
    ///
    /// # Errors
    /// [`ParamError::OutOfRange`] if `n` is outside `[1, MAX_FIBONACCI_DIRECTIONS]` (2^22).
    pub fn fibonacci(n: usize) -> Result<Self, ParamError> {
        ParamError::check("directions", n as f64, "must be in [1, 2^22]", |n| {
            (1.0..=MAX_FIBONACCI_DIRECTIONS as f64).contains(&n)
        })?;
        let weight = 4.0 * core::f64::consts::PI / n as f64;
        let nodes = fibonacci_directions(n)
            .into_iter()
            .map(|d| (V3::new(d.x, d.y, d.z), weight))
            .collect();
        Ok(SphereRule { nodes })
    }

    /// Integral over the sphere of `f(direction)` (solid angle measure).
    pub fn integrate(&self, mut f: impl FnMut(V3<f64>) -> f64) -> f64 {
        self.nodes.iter().map(|&(w, wt)| wt * f(w)).sum()
    }
}

/// The `k`-th point of the Kronecker (additive recurrence) sequence in `dims` dimensions with
/// Roberts' generalised golden ratios: coordinate d is `frac(1/2 + k / phi_dims^(d + 1))`,
/// where phi_dims is the positive root of `x^(dims + 1) = x + 1` (phi_1 is the golden ratio;
/// M. Roberts 2018, "The Unreasonable Effectiveness of Quasirandom Sequences"). Deterministic
/// and evenly spread over the unit cube [0, 1)^dims (low discrepancy), and (almost surely) off
/// every regular grid, so it serves for test points off a table's grid and for reproducible
/// inputs of timing loops.
///
/// Writes the first `min(dims, out.len())` coordinates to `out` (the others are untouched).
pub fn kronecker(k: usize, dims: usize, out: &mut [f64]) {
    // phi_d by the fixed-point iteration x <- (1 + x)^(1 / (d + 1)), a contraction.
    let mut g = 2.0f64;
    for _ in 0..64 {
        g = (1.0 + g).powf(1.0 / (dims as f64 + 1.0));
    }
    for (d, o) in out.iter_mut().enumerate().take(dims) {
        let alpha = g.powi(-(d as i32 + 1));
        *o = (0.5 + k as f64 * alpha).fract();
    }
}

/// A panel of [`adaptive`] with its two halves, ordered by the ratio of its error estimate to
/// its allowance.
struct Panel<const N: usize> {
    lo: f64,
    hi: f64,
    left: [f64; N],
    right: [f64; N],
    diff: f64,
    ratio: f64,
}

impl<const N: usize> PartialEq for Panel<N> {
    fn eq(&self, other: &Self) -> bool {
        self.ratio.total_cmp(&other.ratio).is_eq()
    }
}
impl<const N: usize> Eq for Panel<N> {}
impl<const N: usize> PartialOrd for Panel<N> {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl<const N: usize> Ord for Panel<N> {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.ratio.total_cmp(&other.ratio)
    }
}

/// Bisection budget of [`adaptive`].
const MAX_BISECTIONS: usize = 20_000;

/// Adaptive integration of a vector-valued `f` over [a, b] with an error estimate.
///
/// Each panel is integrated with the 8-point Gauss-Legendre rule, whole and as two halves; the
/// difference of the two estimates bounds the error of the halves (for smooth integrands it
/// overestimates it by orders of magnitude). Panels whose estimate exceeds their share of the
/// tolerance `max(abs_tol, rel_tol * |integral|)` (largest component) and the rounding level
/// (1e-14 of the panel's value) are bisected, worst first, down to a width of 1e-12 of the
/// interval and at most 20,000 times; every panel adds its difference to the error estimate,
/// so the estimate stays honest when the budget or the width limit stops the refinement. `breakpoints` (any order, outside points ignored) start new panels, so narrow
/// peaks placed there are never stepped over. Returns the integral and the summed error
/// estimate.
pub fn adaptive<const N: usize>(
    mut f: impl FnMut(f64) -> [f64; N],
    a: f64,
    b: f64,
    breakpoints: &[f64],
    rel_tol: f64,
    abs_tol: f64,
) -> ([f64; N], f64) {
    let rule = gauss_legendre(8);
    let mut panel = |lo: f64, hi: f64| -> [f64; N] {
        let (c, h) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let mut sum = [0.0; N];
        for &(x, w) in &rule {
            let v = f(c + h * x);
            for (s, v) in sum.iter_mut().zip(v) {
                *s += w * h * v;
            }
        }
        sum
    };
    let mut edges: Vec<f64> = breakpoints
        .iter()
        .copied()
        .filter(|x| *x > a && *x < b)
        .collect();
    edges.extend([a, b]);
    edges.sort_by(f64::total_cmp);
    edges.dedup();
    // A first pass sets the scale of the relative tolerance.
    let mut stack: Vec<(f64, f64, [f64; N])> = Vec::with_capacity(edges.len());
    let mut scale = 0.0_f64;
    for pair in edges.windows(2) {
        let whole = panel(pair[0], pair[1]);
        scale += whole.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        stack.push((pair[0], pair[1], whole));
    }
    let tol = abs_tol.max(rel_tol * scale);
    let min_width = (b - a) * 1e-12;
    // Each panel carries its halves and the ratio of its error estimate to its allowance (its
    // share of the tolerance, or the rounding level of its value); the worst panel is bisected
    // first, so a bisection budget is spent where the error is.
    let mut split = |lo: f64, hi: f64, whole: [f64; N]| -> Panel<N> {
        let mid = 0.5 * (lo + hi);
        let (left, right) = (panel(lo, mid), panel(mid, hi));
        let diff = (0..N).fold(0.0_f64, |m, k| m.max((left[k] + right[k] - whole[k]).abs()));
        let size = (0..N).fold(0.0_f64, |m, k| m.max((left[k] + right[k]).abs()));
        let allowance = (tol * (hi - lo) / (b - a))
            .max(1e-14 * size)
            .max(f64::MIN_POSITIVE);
        let ratio = if hi - lo < min_width {
            0.0
        } else {
            diff / allowance
        };
        Panel {
            lo,
            hi,
            left,
            right,
            diff,
            ratio,
        }
    };
    let mut heap: BinaryHeap<Panel<N>> = stack
        .into_iter()
        .map(|(lo, hi, w)| split(lo, hi, w))
        .collect();
    for _ in 0..MAX_BISECTIONS {
        match heap.peek() {
            Some(worst) if worst.ratio > 1.0 => {}
            _ => break,
        }
        let worst = heap.pop().expect("peeked");
        let mid = 0.5 * (worst.lo + worst.hi);
        heap.push(split(worst.lo, mid, worst.left));
        heap.push(split(mid, worst.hi, worst.right));
    }
    let (mut total, mut error) = ([0.0; N], 0.0);
    for panel in heap {
        for ((t, l), r) in total.iter_mut().zip(panel.left).zip(panel.right) {
            *t += l + r;
        }
        error += panel.diff;
    }
    (total, error)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Gauss rule of the 64-point Gauss-Legendre measure is the n-point Gauss-Legendre
    /// rule, and of the M-point Gauss-Chebyshev measure the n-point Gauss-Chebyshev rule (closed
    /// form: nodes cos((2i - 1) pi / 2n), weights pi / n), both mapped onto other intervals.
    #[test]
    fn the_gauss_rule_of_a_measure_recovers_classical_rules() {
        let fine = gauss_legendre(64);
        for n in [1, 2, 5, 8, 16, 32] {
            let measure: Vec<(f64, f64)> = fine
                .iter()
                .map(|&(x, w)| (3.0 + 2.0 * x, 2.0 * w))
                .collect();
            let rule = gauss_rule_of_measure(&measure, n);
            let mut want: Vec<(f64, f64)> = gauss_legendre(n)
                .iter()
                .map(|&(x, w)| (3.0 + 2.0 * x, 2.0 * w))
                .collect();
            want.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert_eq!(rule.len(), n);
            for (got, want) in rule.iter().zip(&want) {
                assert!(
                    (got.0 - want.0).abs() < 1e-13,
                    "n {n}: {got:?} against {want:?}"
                );
                assert!(
                    (got.1 - want.1).abs() < 1e-13,
                    "n {n}: {got:?} against {want:?}"
                );
            }
        }
        let pi = core::f64::consts::PI;
        let chebyshev = |m: usize| -> Vec<(f64, f64)> {
            (1..=m)
                .map(|i| {
                    (
                        (pi * (2 * i - 1) as f64 / (2 * m) as f64).cos(),
                        pi / m as f64,
                    )
                })
                .collect()
        };
        for n in [3, 7, 12] {
            let rule = gauss_rule_of_measure(&chebyshev(40), n);
            let mut want = chebyshev(n);
            want.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (got, want) in rule.iter().zip(&want) {
                assert!((got.0 - want.0).abs() < 1e-13 && (got.1 - want.1).abs() < 1e-13);
            }
        }
    }

    /// On uneven measures (weights over 30 orders of magnitude, clustered points) the rule
    /// integrates every monomial of degree below 2n as the measure does, to 1e-12 of the
    /// measure's integral of |x|^d; with fewer live points than n it returns them.
    #[test]
    fn the_gauss_rule_of_a_measure_is_exact_to_degree_2n_minus_1() {
        let mut state = 7_u64;
        let mut random = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..50 {
            let m = 20 + case;
            let measure: Vec<(f64, f64)> = (0..m)
                .map(|_| {
                    let x = if random() < 0.5 {
                        0.3 + 1e-3 * random()
                    } else {
                        random()
                    };
                    (x, 10f64.powf(-30.0 * random()))
                })
                .collect();
            let n = 1 + case % 9;
            let rule = gauss_rule_of_measure(&measure, n);
            assert!(!rule.is_empty() && rule.len() <= n);
            assert!(rule.windows(2).all(|w| w[0].0 < w[1].0));
            assert!(rule
                .iter()
                .all(|&(x, w)| (0.0..=1.0).contains(&x) && w > 0.0));
            for d in 0..(2 * rule.len()) as i32 {
                let want: f64 = measure.iter().map(|&(x, w)| w * x.powi(d)).sum();
                let scale: f64 = measure.iter().map(|&(x, w)| w * x.abs().powi(d)).sum();
                let got: f64 = rule.iter().map(|&(x, w)| w * x.powi(d)).sum();
                assert!(
                    (got - want).abs() <= 1e-12 * scale,
                    "case {case} degree {d}: {got} against {want}"
                );
            }
        }
        let two = [(0.25, 1.0), (0.5, 0.0), (0.75, 3.0)];
        let rule = gauss_rule_of_measure(&two, 5);
        assert_eq!(rule.len(), 2);
        for (got, want) in rule.iter().zip([(0.25, 1.0), (0.75, 3.0)]) {
            assert!((got.0 - want.0).abs() < 1e-15 && (got.1 - want.1).abs() < 1e-15);
        }
        assert_eq!(gauss_rule_of_measure(&[(0.4, 2.0)], 3), vec![(0.4, 2.0)]);
        assert!(gauss_rule_of_measure(&[(0.4, 0.0)], 3).is_empty());
        assert!(gauss_rule_of_measure(&[], 3).is_empty());
    }

    /// The rational QL against closed forms: the matrix with diagonal a and off-diagonal b has
    /// the eigenvalues `a + 2 b cos(k pi / (n + 1))`, k = 1..n (a = 0 makes every sweep start
    /// from a zero diagonal entry); a zero coupling splits the matrix into blocks with their
    /// own eigenvalues; a diagonal matrix is its own.
    #[test]
    fn rational_ql_finds_closed_form_eigenvalues() {
        let pi = core::f64::consts::PI;
        let sorted = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v
        };
        for (a, b) in [(2.0, -1.0), (0.0, 1.0), (-3.0, 1e-3), (1e6, 5e5)] {
            for n in [1, 2, 3, 8, 17, 32] {
                let mut d = vec![a; n];
                tridiagonal_eigenvalues(&mut d, &vec![b; n]);
                let want = sorted(
                    (1..=n)
                        .map(|k| a + 2.0 * b * (k as f64 * pi / (n + 1) as f64).cos())
                        .collect(),
                );
                let scale = a.abs() + 2.0 * b.abs();
                for (got, want) in sorted(d).iter().zip(&want) {
                    assert!(
                        (got - want).abs() <= 1e-14 * scale,
                        "a {a}, b {b}, n {n}: {got} against {want}"
                    );
                }
            }
        }
        let mut d = vec![1.0, 1.0, 5.0, 5.0];
        tridiagonal_eigenvalues(&mut d, &[2.0, 0.0, 3.0, 0.0]);
        for (got, want) in sorted(d).iter().zip([-1.0, 2.0, 3.0, 8.0]) {
            assert!((got - want).abs() < 1e-14, "{got} against {want}");
        }
        let mut d = vec![4.0, -1.0, 0.0];
        tridiagonal_eigenvalues(&mut d, &[0.0; 3]);
        assert_eq!(sorted(d), vec![-1.0, 0.0, 4.0]);
    }

    #[test]
    fn gauss_legendre_is_exact_for_degree_2n_minus_1() {
        for n in [1, 2, 5, 8, 16] {
            let rule = gauss_legendre(n);
            for d in 0..(2 * n) {
                let got: f64 = rule.iter().map(|&(x, w)| w * x.powi(d as i32)).sum();
                let want = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                assert!((got - want).abs() < 1e-14, "n {n} degree {d}: {got}");
            }
        }
    }

    #[test]
    fn the_asymptotic_rule_agrees_with_the_recurrence() {
        // Above NEWTON_MAX_NODES the interior nodes come from Stieltjes' series: compare them
        // with Newton's method on the recurrence (the n <= 1000 method) node by node.
        for n in [1001, 1536, 2047, 4000] {
            let fast = gauss_legendre(n);
            assert_eq!(fast.len(), n);
            let (mut max_x, mut max_w) = (0.0_f64, 0.0_f64);
            for (i, &(x, w)) in fast.iter().enumerate() {
                let (xr, wr) = newton_node(n, initial_guess(n, i));
                max_x = max_x.max((x - xr).abs());
                max_w = max_w.max(((w - wr) / wr).abs());
            }
            // The recurrence's own weights carry O(n eps) rounding (2.3e-13 measured at
            // n = 1001, 1.4e-12 at 4000), so the weights agree to that, the nodes to 2 ulp.
            assert!(
                max_x <= 4.5e-16 && max_w <= 1e-15 * n as f64,
                "n {n}: {max_x:e} {max_w:e}"
            );
            let sum: f64 = fast.iter().map(|&(_, w)| w).sum();
            assert!((sum - 2.0).abs() < 1e-13, "n {n}: {sum}");
            let x4: f64 = fast.iter().map(|&(x, w)| w * x.powi(4)).sum();
            assert!((x4 - 0.4).abs() < 1e-13, "n {n}: {x4}");
        }
        // Gamma(1000) / Gamma(1000.5) to 30 digits (mpmath): 0.0316267296956575176880099065058.
        // exp(-(ln(z) / 2 + ...)) at an exponent of 3.45 rounds to about 4 eps relative.
        let error = (gamma_ratio(1000.0) / 0.031_626_729_695_657_52 - 1.0).abs();
        assert!(error < 1e-15, "{error:e}");
    }

    #[test]
    fn sphere_rule_weights_sum_to_four_pi_and_integrate_x_squared() {
        let r = SphereRule::new(8, 8, 16);
        assert!((r.integrate(|_| 1.0) - 4.0 * core::f64::consts::PI).abs() < 1e-12);
        let x2 = r.integrate(|w| w.x * w.x);
        assert!((x2 - 4.0 * core::f64::consts::PI / 3.0).abs() < 1e-12);
    }

    #[test]
    fn kronecker_uses_the_generalised_golden_ratio_and_fills_the_cube() {
        let mut u = [0.0; 2];
        kronecker(1, 1, &mut u);
        // One dimension: frac(1/2 + 1/phi), phi the golden ratio; the second slot is untouched.
        let phi = 0.5 * (1.0 + 5f64.sqrt());
        assert!((u[0] - (0.5 + 1.0 / phi).fract()).abs() < 1e-14, "{u:?}");
        assert_eq!(u[1], 0.0);
        // Two dimensions: every cell of a 4 x 4 grid gets a share of 1024 points.
        let mut counts = [0usize; 16];
        for k in 0..1024 {
            kronecker(k, 2, &mut u);
            assert!(u.iter().all(|x| (0.0..1.0).contains(x)));
            counts[(4.0 * u[0]) as usize * 4 + (4.0 * u[1]) as usize] += 1;
        }
        assert!(counts.iter().all(|&c| (56..=72).contains(&c)), "{counts:?}");
    }

    #[test]
    fn adaptive_integrates_a_narrow_peak_to_its_tolerance() {
        // int_{-1}^{1} 1 / (1e-6 + x^2) dx = 2e3 atan(1e3): a peak of width 1e-3.
        let exact = 2.0 * 1e3 * (1e3_f64).atan();
        let (v, err) = adaptive(|x| [1.0 / (1e-6 + x * x)], -1.0, 1.0, &[0.0], 1e-12, 0.0);
        assert!((v[0] - exact).abs() < 1e-9 * exact, "{} vs {exact}", v[0]);
        assert!(err < 1e-9 * exact && err >= 0.0);
    }
}
