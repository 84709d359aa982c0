//! Every public function generic over [`Real`] traced to shader code: the WGSL text must pass
//! naga's parser and validator, and the traced graph interpreted in `f32`
//! ([`Graph::eval_f32`]) must reproduce the `f32` instantiation bit for bit on about 200
//! deterministic inputs per function, hard cases included (grazing directions, h = +-1,
//! wi = +-wo, phi = 0 and +-pi, variance 1e-4 and 100, sigma_a 0 and 10, eta = 1.0001, large
//! cuticle tilts; for spherical harmonics the poles z = +-1, rotations at the identity, in
//! 90-degree steps and near gimbal lock, zero and one-hot coefficient vectors).
//!
//! `coverage_matches_the_source` scans `src/` so that a new public generic function without a
//! trace test here fails the suite.

use hairmath::absorption::segment_length;
use hairmath::absorption::{segment_transmittance, PathLength};
use hairmath::azimuthal::{
    attenuations, attenuations_at_offset, attenuations_from_fresnel, exit_angle,
    exit_angle_of_offset, logistic, logistic_cdf, refracted_offset, sample_trimmed_logistic,
    sample_wrapped_gaussian, trimmed_logistic, trimmed_mass, wrapped_gaussian,
};
use hairmath::azimuthal::{FibrePath, Refraction, TrimmedLogistic};
use hairmath::bcsdf::{
    query_of, query_parameters, trace_eval, trace_model, traced_inputs, Bcsdf, ChiangFarField,
    ChiangHair, ChiangUniforms, FarFieldRule, Model, Query, RandomNumbers, SampledBcsdf,
    UniformBlock, UniformsIn,
};
use hairmath::fresnel::{
    bravais_eta_parallel, bravais_eta_perpendicular, fresnel_dielectric, fresnel_schlick,
};
use hairmath::fresnel::{fresnel_from_outside, fresnel_of_cosines};
use hairmath::geometry::{
    azimuth_between, fibre_angles, fibre_frame, local_direction, local_directions,
    local_fibre_angles, local_sin_cos_theta, sin_cos_theta, FibreAngles, V3,
};
use hairmath::lobe::{
    deon_lobe, deon_lobe_sample_cos_theta, gaussian_lobe, hg_circle_factor, hg_gerard_printed,
    DeonLobe, HenyeyGreenstein,
};
use hairmath::lobe::{i0, i0e_split, i0e_split_reduced, log_i0, log_i0e, BesselForm};
use hairmath::lut::axis_cell;
use hairmath::params::{HairParams, HairValues};
use hairmath::real::{horner, pi, safe_asin, safe_sqrt, trace, wrap_angle, Graph, Real, Traced};
use hairmath::real::{horner_named, NamedConstant};

/// A named table of polynomial coefficients (Abramowitz and Stegun 9.8.2's first five).
static COEFFICIENTS: NamedConstant = NamedConstant {
    name: "COEFFICIENTS",
    meaning: "a test table",
    values: &[0.39894228, 0.01328592, 0.00225319, -0.00157565, 0.00916281],
};
use hairmath::real::{ArgType, Parameter, ResultType};
use hairmath::sh::{eval_sh, eval_sh_into};
use hairmath::sh::{product, triple_product_integral, ProductPlan};
use hairmath::sh::{
    rotate_band1, rotate_band2, rotate_bands012, rotate_with_blocks, rotate_zonal_into,
    rotation_blocks,
};
use std::collections::BTreeSet;
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// Inputs per function (at least; special-value combinations come first).
const N: usize = 200;

// ---------------------------------------------------------------------------------------------
// The check.

/// Validates `graph`'s WGSL with naga and compares `graph.eval_f32` with `f32_fn` bit for bit on
/// every input row. Fails listing the differing rows; a NaN from the `f32` code also fails
/// (every input row lies in the function's documented domain).
fn check(name: &str, inputs: &[Vec<f32>], graph: &Graph, f32_fn: impl Fn(&[f32]) -> Vec<f32>) {
    let words: Vec<&str> = name.split(|c: char| !c.is_ascii_alphanumeric()).collect();
    let ident = words
        .iter()
        .filter(|w| !w.is_empty())
        .copied()
        .collect::<Vec<_>>();
    let wgsl = graph.to_wgsl(&ident.join("_"));
    if let Err(error) = validate_wgsl(&wgsl) {
        panic!("{name}: naga rejects the traced WGSL:\n{wgsl}\n{error}");
    }
    let mut failures = Vec::new();
    for x in inputs {
        let (traced, cpu) = (graph.eval_f32(x), f32_fn(x));
        let same = traced.len() == cpu.len()
            && traced
                .iter()
                .zip(&cpu)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same || cpu.iter().any(|v| v.is_nan()) {
            failures.push(format!("  in {x:?}\n  traced {traced:?}\n  f32    {cpu:?}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{name}: {} of {} inputs differ or give NaN, first ones:\n{}",
        failures.len(),
        inputs.len(),
        failures[..failures.len().min(8)].join("\n")
    );
}

/// The error of naga's WGSL front end or validator (all checks, all capabilities), if any.
fn validate_wgsl(src: &str) -> Result<(), String> {
    use naga::valid::{Capabilities, ValidationFlags, Validator};
    let module = naga::front::wgsl::parse_str(src).map_err(|e| e.emit_to_string(src))?;
    Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| e.emit_to_string(src))?;
    Ok(())
}

/// `case!(label, inputs, |x| body)`: traces `body` (an expression of the argument slice `x`
/// returning `Vec<R>`, written once and instantiated for both `Traced` and `f32`) and runs
/// [`check`] on it.
macro_rules! case {
    ($label:expr, $inputs:expr, |$x:ident| $body:expr) => {{
        let inputs: Vec<Vec<f32>> = $inputs;
        let graph = trace(inputs[0].len(), |$x: &[Traced]| $body);
        check(&$label, &inputs, &graph, |$x: &[f32]| $body);
    }};
}

/// `model_case!(label, model, extra, result, inputs, |m, x| body)`: traces `body` through the
/// model contract ([`trace_model`]: the first argument is the model's uniforms as a named
/// struct, then the parameters `extra`; `m` is the model rebuilt from them, `x` the inputs of
/// `extra`) and checks it against the same body on the `f32` model built from each row's
/// uniforms. Each input row holds the uniforms' values, then those of `extra`.
macro_rules! model_case {
    ($label:expr, $model:expr, $extra:expr, $result:expr, $inputs:expr, |$m:ident, $x:ident| $body:expr) => {{
        let model = $model;
        let inputs: Vec<Vec<f32>> = $inputs;
        let width = model.uniforms().to_values().len();
        let graph = trace_model(
            &model,
            UniformsIn::Argument,
            $extra,
            $result,
            |$m, $x: &[Traced]| $body,
        );
        check(&$label, &inputs, &graph, |row: &[f32]| {
            let $m = &model.with_uniforms::<f32>(UniformBlock::from_values(&row[..width]));
            let $x = &row[width..];
            $body
        });
    }};
}

/// One `#[test]` per entry, and `COVERED`: the function names the entries test, as
/// [`scan_public_generic_functions`] spells them.
macro_rules! traced_tests {
    ($($test:ident [$($covers:literal),+] $body:block)*) => {
        $(#[test] fn $test() $body)*
        pub const COVERED: &[&str] = &[$($($covers),+),*];
    };
}

// ---------------------------------------------------------------------------------------------
// Deterministic inputs.

/// The domain of one scalar argument: uniform on [lo, hi] (log-uniform when lo > 0 and the
/// range spans three decades), with probability 1/4 one of the special values instead.
#[derive(Clone, Copy)]
struct Arg {
    lo: f64,
    hi: f64,
    special: &'static [f64],
}

const fn arg(lo: f64, hi: f64, special: &'static [f64]) -> Arg {
    Arg { lo, hi, special }
}

const ONE_MINUS_ULP: f64 = 1.0 - 1.0 / 16_777_216.0; // largest f32 below 1
const SIN: Arg = arg(-1.0, 1.0, &[-1.0, 0.0, 1.0]); // also h and signed cosines
const UNIT: Arg = arg(0.0, 1.0, &[0.0, 1.0]); // cosines >= 0, reflectances, transmittances
const U: Arg = arg(0.0, 1.0, &[0.0, 0.5, ONE_MINUS_ULP]); // uniform samples in [0, 1)
const ETA: Arg = arg(1.0001, 2.5, &[1.0001, 1.55, 2.5]);
const ANGLE: Arg = arg(-PI, PI, &[0.0, PI, -PI]);
const HALF_ANGLE: Arg = arg(-FRAC_PI_2, FRAC_PI_2, &[0.0, FRAC_PI_2, -FRAC_PI_2]);
const LOBE: Arg = arg(0.0, 3.0, &[0.0, 1.0, 2.0, 3.0]);
const VARIANCE: Arg = arg(1e-4, 100.0, &[1e-4, 100.0]);
const BETA: Arg = arg(1e-2, 10.0, &[1e-2, 10.0]); // standard deviation: variance 1e-4 to 100
const SCALE: Arg = arg(1e-3, 10.0, &[1e-3, 10.0]); // logistic scale s
const SIGMA_A: Arg = arg(0.0, 10.0, &[0.0, 10.0]);
/// cos(theta_t) >= sqrt(1 - 1/eta^2), 0.01414 for eta = 1.0001.
const COS_THETA_T: Arg = arg(0.01414, 1.0, &[0.01414, 1.0]);
const HG_G: Arg = arg(-0.99, 0.99, &[0.0, 0.752, -0.99, 0.99]);
const BESSEL_X: Arg = arg(1e-6, 1e4, &[0.0, -1.0, 3.75, 3.7499998, 20.0, 1e4]);
const I0_X: Arg = arg(-80.0, 80.0, &[0.0, 3.75, -3.75, 80.0, -80.0]);
/// No -0.0: see `signed_zero_through_max_is_reproduced`.
const SQRT_X: Arg = arg(-1.0, 100.0, &[0.0, -1e-7, 1.0]);
const ASIN_X: Arg = arg(-1.5, 1.5, &[-1.5, -1.0, 0.0, 1.0, 1.5]);
const WRAP_X: Arg = arg(-20.0, 20.0, &[0.0, PI, -PI, 2.0 * PI, -3.0 * PI]);
const HORNER_X: Arg = arg(-4.0, 4.0, &[0.0, 1.0, -1.0]);

/// Chiang materials: (beta_m, beta_n, alpha, eta, sigma_a, variance override for all lobes).
type Material = (f64, f64, f64, f64, [f64; 3], Option<f64>);
const MATERIALS: &[Material] = &[
    (0.3, 0.3, 0.0349, 1.55, [0.545, 0.906, 1.781], None), // brown hair, 2 degree tilt
    (0.0137, 0.01, 0.0, 1.0001, [0.0; 3], None),           // v0 = 1e-4, eta near 1, no absorption
    (1.0, 1.0, -1.5, 2.4, [10.0; 3], None),                // roughest, large tilt, opaque
    (0.1, 0.6, 1.5, 1.55, [0.0, 1.0, 10.0], None),
    (0.5, 0.2, 0.0, 1.55, [0.2, 0.4, 0.8], Some(1e-4)),
    (0.5, 0.2, 0.1, 1.55, [0.2, 0.4, 0.8], Some(100.0)),
];

fn params((beta_m, beta_n, alpha, eta, sigma_a, _): Material) -> HairParams {
    let values = HairValues {
        beta_m,
        beta_n,
        alpha,
        eta,
        sigma_a,
    };
    HairParams::try_from(values).unwrap()
}

/// A splitmix64 stream of deterministic pseudo-random inputs.
struct Gen(u64);

impl Gen {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f64) as usize).min(n - 1)
    }
    fn pick(&mut self, a: &Arg) -> f64 {
        if !a.special.is_empty() && self.uniform() < 0.25 {
            a.special[self.below(a.special.len())]
        } else if a.lo > 0.0 && a.hi > 1e3 * a.lo {
            a.lo * (a.hi / a.lo).powf(self.uniform())
        } else {
            a.lo + (a.hi - a.lo) * self.uniform()
        }
    }
    /// sin and cos of a longitudinal angle, grazing (sin = +-1) and normal (sin = 0) included.
    fn sin_cos(&mut self) -> [f64; 2] {
        let s = self.pick(&SIN);
        [s, (1.0 - s * s).sqrt()]
    }
    fn dir_with_phi(&mut self, phi: f64) -> [f64; 3] {
        let [s, c] = self.sin_cos();
        [s, c * phi.cos(), c * phi.sin()]
    }
    /// A unit direction in the local frame (tangent +X).
    fn dir(&mut self) -> [f64; 3] {
        let phi = self.pick(&ANGLE);
        self.dir_with_phi(phi)
    }
    /// wi and wo: equal, opposite, at relative azimuth 0 or pi, or independent.
    fn pair(&mut self) -> Vec<f64> {
        let phi = self.pick(&ANGLE);
        let wi = self.dir_with_phi(phi);
        let wo = match self.below(6) {
            0 => wi,
            1 => wi.map(|v| -v),
            2 => self.dir_with_phi(phi),
            3 => self.dir_with_phi(phi + PI),
            _ => self.dir(),
        };
        [wi, wo].concat()
    }
    /// The uniforms ([`ChiangUniforms`]) of one of `MATERIALS`, with its variance override
    /// (which no beta_m reaches) written into the lobe fields by name.
    fn hair(&mut self) -> Vec<f64> {
        let m = MATERIALS[self.below(MATERIALS.len())];
        let mut u = ChiangUniforms::new(&params(m));
        if let Some(v) = m.5 {
            let [r, tt, trt] = [v, 0.25 * v, 4.0 * v].map(DeonLobe::<f64>::new);
            (u.variance_r, u.inv_variance_r, u.lobe_norm_r) = (v, r.inv_v, r.norm);
            (u.variance_tt, u.inv_variance_tt, u.lobe_norm_tt) = (0.25 * v, tt.inv_v, tt.norm);
            (u.variance_trt, u.inv_variance_trt, u.lobe_norm_trt) = (4.0 * v, trt.inv_v, trt.norm);
        }
        u.to_values()
    }
    /// A query's arguments: a direction pair and an offset.
    fn query(&mut self) -> Vec<f64> {
        [self.pair(), vec![self.pick(&SIN)]].concat()
    }
    /// Uniform numbers for sampling, in the order of [`RandomNumbers`]' fields.
    fn numbers(&mut self) -> Vec<f64> {
        vec![self.pick(&U), self.pick(&U), self.pick(&U), self.pick(&U)]
    }
}

/// `N` rows built by `row`, rounded to `f32`.
fn rows(mut row: impl FnMut(&mut Gen) -> Vec<f64>) -> Vec<Vec<f32>> {
    let mut g = Gen(0x5eed);
    (0..N)
        .map(|_| row(&mut g).iter().map(|&v| v as f32).collect())
        .collect()
}

/// Rows of independent scalar arguments: every combination of special values first (or, when
/// there are too many, each special value of each argument with the others random), then
/// random rows up to `N`.
fn scalars(args: &[Arg]) -> Vec<Vec<f32>> {
    let mut g = Gen(0x5ca1);
    let combinations: usize = args.iter().map(|a| a.special.len().max(1)).product();
    let mut out: Vec<Vec<f64>> = Vec::new();
    if combinations <= N / 2 {
        for k in 0..combinations {
            // k in mixed radix: one digit per argument.
            let mut rest = k;
            let mut row = Vec::new();
            for a in args {
                let n = a.special.len().max(1);
                row.push(
                    a.special
                        .get(rest % n)
                        .copied()
                        .unwrap_or_else(|| g.pick(a)),
                );
                rest /= n;
            }
            out.push(row);
        }
    } else {
        for (j, a) in args.iter().enumerate() {
            for &s in a.special {
                let row = args.iter().enumerate().map(|(i, b)| match i == j {
                    true => s,
                    false => g.pick(b),
                });
                out.push(row.collect());
            }
        }
    }
    while out.len() < N {
        out.push(args.iter().map(|a| g.pick(a)).collect());
    }
    out.iter()
        .map(|r| r.iter().map(|&v| v as f32).collect())
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Generic plumbing between argument slices and the library's types.

fn arr<R: Copy, const K: usize>(x: &[R]) -> [R; K] {
    core::array::from_fn(|i| x[i])
}
fn v3<R: Real>(x: &[R]) -> V3<R> {
    V3::new(x[0], x[1], x[2])
}
fn of_v3<R: Real>(v: V3<R>) -> Vec<R> {
    vec![v.x, v.y, v.z]
}
fn of_pair<R: Real>((a, b): (R, R)) -> Vec<R> {
    vec![a, b]
}
fn angles<R: Real>(x: &[R]) -> FibreAngles<R> {
    FibreAngles {
        sin_theta_i: x[0],
        cos_theta_i: x[1],
        sin_theta_o: x[2],
        cos_theta_o: x[3],
        phi: x[4],
    }
}
fn of_angles<R: Real>(a: FibreAngles<R>) -> Vec<R> {
    vec![
        a.sin_theta_i,
        a.cos_theta_i,
        a.sin_theta_o,
        a.cos_theta_o,
        a.phi,
    ]
}
/// The number of scalars of the uniforms ([`ChiangUniforms`]); a query's arguments follow.
fn mat() -> usize {
    ChiangUniforms::<f64>::fields()
        .iter()
        .map(|f| f.width)
        .sum()
}
/// The uniforms of a random material, then a query (wi, wo, h).
fn chiang_rows() -> Vec<Vec<f32>> {
    rows(|g| [g.hair(), g.query()].concat())
}
/// `1 / x`.
fn recip<R: Real>(x: R) -> R {
    R::c(1.0) / x
}
/// The cosine of the transmitted direction by Snell's law, for incidence from outside at
/// cosine `cos_i` into relative index `eta >= 1`.
fn snell_cos_t<R: Real>(cos_i: R, eta: R) -> R {
    let sin2_t = (R::c(1.0) - cos_i * cos_i) * recip(eta * eta);
    safe_sqrt(R::c(1.0) - sin2_t)
}
/// Constants of the working precision.
fn consts<R: Real>(values: &[f64]) -> Vec<R> {
    values.iter().map(|&v| R::c(v)).collect()
}
/// [`RandomNumbers`] from four arguments.
fn numbers<R: Real>(x: &[R]) -> RandomNumbers<R> {
    RandomNumbers {
        lobe: x[0],
        longitudinal: x[1],
        cone: x[2],
        offset: x[3],
    }
}
/// The sampling arguments: wo, h, then the four numbers.
fn sample_parameters() -> Vec<Parameter> {
    let mut p = vec![Parameter::argument("wo", ArgType::Vec3)];
    for name in ["h", "lobe", "longitudinal", "cone", "offset"] {
        p.push(Parameter::argument(name, ArgType::Scalar));
    }
    p
}

/// Direction pairs `[wi, wo]` every model's row set starts with: along the tangent (equal,
/// opposite, with the other direction in the normal plane), grazing from opposite ends,
/// phi = 0 and pi in the normal plane, wi = -wo off the normal plane.
const HARD_PAIRS: &[[f64; 6]] = &[
    [1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 0.0, 0.6, 0.8],
    [0.0, 0.6, 0.8, -1.0, 0.0, 0.0],
    [0.999_999_9, 4.47e-4, 0.0, -0.999_999_9, 0.0, 4.47e-4],
    [0.0, 1.0, 0.0, 0.0, 1.0, 0.0],
    [0.0, 1.0, 0.0, 0.0, -1.0, 0.0],
    [-0.3, 0.0, 0.953_939_2, 0.3, 0.0, -0.953_939_2],
];

/// Rows of a model's uniforms then a direction pair: each of `materials` materials
/// (`uniforms(k)`) with each of [`HARD_PAIRS`], then random materials and pairs.
fn material_rows(materials: usize, uniforms: impl Fn(usize) -> Vec<f64>) -> Vec<Vec<f32>> {
    let mut first = Vec::new();
    for k in 0..materials {
        for p in HARD_PAIRS {
            first.push([uniforms(k), p.to_vec()].concat());
        }
    }
    listed_then(first, |g| [uniforms(g.below(materials)), g.pair()].concat())
}

/// Listed rows first (the hard cases), then rows built by `row` up to `N`, rounded to `f32`.
fn listed_then(first: Vec<Vec<f64>>, row: impl FnMut(&mut Gen) -> Vec<f64>) -> Vec<Vec<f32>> {
    let random = rows(row);
    let first: Vec<Vec<f32>> = first
        .iter()
        .map(|r| r.iter().map(|&v| v as f32).collect())
        .collect();
    let n = N.max(first.len());
    first.into_iter().chain(random).take(n).collect()
}

/// Unit directions for spherical harmonics with the hard cases first: the poles (where x and y
/// vanish and every m != 0 term must be exactly zero), the axes, a direction 1e-4 rad from the
/// pole.
const SH_DIRECTIONS: &[[f64; 3]] = &[
    [0.0, 0.0, 1.0],
    [0.0, 0.0, -1.0],
    [1.0, 0.0, 0.0],
    [-1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, -1.0, 0.0],
    [1e-4, 0.0, 0.999_999_995],
    [0.0, -1e-4, -0.999_999_995],
    [0.6, 0.0, 0.8],
    [0.0, 0.6, -0.8],
];

/// Rotation matrices (row-major) with the hard cases first: the identity, every 90-degree step
/// about each axis and compositions of two (signed permutations, the exact-zero patterns),
/// Z-Y-Z Euler angles at and next to gimbal lock (beta = 0, +-1e-4, pi - 1e-4, pi), rotations
/// 1e-3 and 1e-6 rad from the identity.
fn hard_rotations() -> Vec<[f64; 9]> {
    let mut out = vec![mat_to_rows(IDENTITY)];
    let quarter = |axis: usize, k: usize| {
        let (c, s) = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][k % 4];
        axis_rotation(axis, c, s)
    };
    for axis in 0..3 {
        for k in 1..4 {
            out.push(mat_to_rows(quarter(axis, k)));
        }
    }
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        out.push(mat_to_rows(mat_mul(quarter(a, 1), quarter(b, 1))));
        out.push(mat_to_rows(mat_mul(quarter(a, 3), quarter(b, 2))));
    }
    for beta in [0.0, 1e-4, -1e-4, PI - 1e-4, PI] {
        for (alpha, gamma) in [(0.3, -0.3), (1.1, 2.0), (-2.5, 0.7)] {
            out.push(mat_to_rows(euler_zyz(alpha, beta, gamma)));
        }
    }
    for angle in [1e-3, 1e-6] {
        for axis in 0..3 {
            out.push(mat_to_rows(axis_rotation(
                axis,
                f64::cos(angle),
                f64::sin(angle),
            )));
        }
    }
    out
}

type Mat = [[f64; 3]; 3];
const IDENTITY: Mat = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn mat_mul(a: Mat, b: Mat) -> Mat {
    core::array::from_fn(|i| core::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}
fn mat_to_rows(m: Mat) -> [f64; 9] {
    core::array::from_fn(|i| m[i / 3][i % 3])
}
/// The rotation about coordinate axis `axis` by the angle with cosine `c` and sine `s`.
fn axis_rotation(axis: usize, c: f64, s: f64) -> Mat {
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = IDENTITY;
    (m[i][i], m[i][j], m[j][i], m[j][j]) = (c, -s, s, c);
    m
}
fn euler_zyz(alpha: f64, beta: f64, gamma: f64) -> Mat {
    let rz = |a: f64| axis_rotation(2, a.cos(), a.sin());
    mat_mul(
        mat_mul(rz(alpha), axis_rotation(1, beta.cos(), beta.sin())),
        rz(gamma),
    )
}

impl Gen {
    /// A unit direction for SH evaluation: one of `SH_DIRECTIONS` with probability 1/4, else
    /// uniform on the sphere.
    fn sphere(&mut self) -> [f64; 3] {
        if self.uniform() < 0.25 {
            return SH_DIRECTIONS[self.below(SH_DIRECTIONS.len())];
        }
        let z = 2.0 * self.uniform() - 1.0;
        let phi = self.pick(&ANGLE);
        let s = (1.0 - z * z).sqrt();
        [s * phi.cos(), s * phi.sin(), z]
    }
    /// A uniformly random rotation (Shoemake's unit quaternion), row-major.
    fn rotation(&mut self) -> [f64; 9] {
        let (u1, u2, u3) = (
            self.uniform(),
            2.0 * PI * self.uniform(),
            2.0 * PI * self.uniform(),
        );
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        let [w, x, y, z] = [a * u2.sin(), a * u2.cos(), b * u3.sin(), b * u3.cos()];
        mat_to_rows([
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ])
    }
    /// `n` SH coefficients: all zero, one-hot, all one, or uniform in [-1, 1].
    fn coefficients(&mut self, n: usize) -> Vec<f64> {
        match self.below(8) {
            0 => vec![0.0; n],
            1 => {
                let k = self.below(n);
                (0..n).map(|i| f64::from(u8::from(i == k))).collect()
            }
            2 => vec![1.0; n],
            _ => (0..n).map(|_| 2.0 * self.uniform() - 1.0).collect(),
        }
    }
    /// Two coefficient vectors of `n` each: independent, equal, or opposite.
    fn coefficient_pair(&mut self, n: usize) -> Vec<f64> {
        let a = self.coefficients(n);
        let b = match self.below(4) {
            0 => a.clone(),
            1 => a.iter().map(|v| -v).collect(),
            _ => self.coefficients(n),
        };
        [a, b].concat()
    }
}

/// A rotation then `n` coefficients: the hard rotations (with random coefficients, and with
/// zero coefficients for the first), then random rotations (one in four a hard one).
fn rotation_rows(n: usize) -> Vec<Vec<f32>> {
    let hard = hard_rotations();
    let mut g = Gen(0x0707a7e);
    let mut first: Vec<Vec<f64>> = hard
        .iter()
        .map(|r| [&r[..], &g.coefficients(n)].concat())
        .collect();
    first.push([&hard[0][..], &vec![0.0; n]].concat());
    first.push([&hard[1][..], &vec![0.0; n]].concat());
    listed_then(first, |g| {
        let r = if g.below(4) == 0 {
            hard[g.below(hard.len())]
        } else {
            g.rotation()
        };
        [&r[..], &g.coefficients(n)].concat()
    })
}
/// The row-major 3x3 matrix of the first nine arguments.
fn mat3<R: Real>(x: &[R]) -> [[R; 3]; 3] {
    [arr(&x[0..3]), arr(&x[3..6]), arr(&x[6..9])]
}
/// Directions with every entry of `SH_DIRECTIONS` first.
fn sh_direction_rows() -> Vec<Vec<f32>> {
    let first = SH_DIRECTIONS.iter().map(|d| d.to_vec()).collect();
    listed_then(first, |g| g.sphere().to_vec())
}

// ---------------------------------------------------------------------------------------------
// The functions.

/// The classic real-time models: Kajiya-Kay, TressFX, Scheuermann.
mod classic;
/// The composed model (`hairmath::models::ComposedHair`).
mod composed;
/// The Frostbite models (`hairmath::models::{Frostbite, FrostbiteRefit}`).
mod frostbite;
/// Gerard's spherical-harmonic shading (`hairmath::models::gerard_sh`).
mod gerard_sh;
/// The closed forms of the real-time models (`hairmath::models`).
mod models;
/// The crossing test of the transmittance bakers (`hairmath::strands`).
mod strands;
/// The structure the traces keep: functions, loops, baked uniforms.
mod structure;
/// Table fetches ([`Real::sample_table`]) and the models that read tables.
mod tables;
/// The Unreal models (`hairmath::models::{Karis, KarisRefit}`).
mod unreal;
/// Shader code with varying inputs and the generic derivations of the uniforms.
mod varying;

traced_tests! {
    real_pi ["pi"] {
        case!("pi", vec![vec![]], |_x| vec![pi()]);
    }
    real_safe_sqrt ["safe_sqrt"] {
        case!("safe_sqrt", scalars(&[SQRT_X]), |x| vec![safe_sqrt(x[0])]);
    }
    real_safe_asin ["safe_asin"] {
        case!("safe_asin", scalars(&[ASIN_X]), |x| vec![safe_asin(x[0])]);
    }
    real_wrap_angle ["wrap_angle"] {
        case!("wrap_angle", scalars(&[WRAP_X]), |x| vec![wrap_angle(x[0])]);
    }
    real_named_constants ["NamedConstant::get", "NamedConstant::at", "horner_named"] {
        case!("named constants", vec![vec![]], |_x| {
            vec![hairmath::real::PI.get(), hairmath::real::TINY.get(), COEFFICIENTS.at(2)]
        });
        case!("horner_named", scalars(&[HORNER_X]), |x| vec![horner_named(x[0], &COEFFICIENTS)]);
    }
    real_horner ["horner"] {
        let as_9_8_2 = [0.39894228, 0.01328592, 0.00225319, -0.00157565, 0.00916281];
        for c in [&[][..], &[2.5], &[1.0, -1.0, 0.5], &as_9_8_2] {
            case!(format!("horner({c:?})"), scalars(&[HORNER_X]), |x| vec![horner(x[0], c)]);
        }
    }

    bcsdf_hair_sample_weight ["HairSample::weight"] {
        // S per channel and the pdf, 0 included (the weight is then 0).
        const PDF: Arg = arg(0.0, 100.0, &[0.0, 1e-30, 1.0]);
        case!("HairSample::weight", scalars(&[SIGMA_A, SIGMA_A, SIGMA_A, PDF]), |x| {
            let sample = hairmath::bcsdf::HairSample {
                wi: V3::new(x[0], x[1], x[2]),
                value: [x[0], x[1], x[2]],
                pdf: x[3],
            };
            sample.weight().to_vec()
        });
    }

    geometry_v3 [
        "V3::new", "V3::from_f64", "V3::dot", "V3::cross", "V3::scale", "V3::sub", "V3::add",
        "V3::to_v3", "V3::from_v3"
    ] {
        use hairmath::world::WorldVector;
        let inputs = rows(|g| [g.pair(), vec![g.pick(&WRAP_X)]].concat());
        case!("V3", inputs, |x| {
            let (a, b) = (V3::new(x[0], x[1], x[2]), v3(&x[3..6]));
            let (cross, scale_sub) = (of_v3(a.cross(b)), of_v3(a.scale(x[6]) - b));
            let add = of_v3(a + WorldVector::from_v3(b.to_v3()));
            [cross, scale_sub, add, vec![a.dot(b)], of_v3(V3::from_f64(0.1, -2.0, 1e-30))].concat()
        });
    }
    geometry_fibre_angles_methods [
        "FibreAngles::theta_i", "FibreAngles::theta_o", "FibreAngles::theta_h",
        "FibreAngles::theta_d"
    ] {
        let inputs = rows(|g| [&g.sin_cos()[..], &g.sin_cos()[..], &[g.pick(&ANGLE)]].concat());
        case!("FibreAngles", inputs, |x| {
            let a = angles(x);
            vec![a.theta_i(), a.theta_o(), a.theta_h(), a.theta_d()]
        });
    }
    geometry_sin_cos_theta ["sin_cos_theta"] {
        let inputs = rows(|g| [g.dir(), g.dir()].concat());
        case!("sin_cos_theta", inputs, |x| of_pair(sin_cos_theta(v3(x), v3(&x[3..]))));
    }
    geometry_local_sin_cos_theta ["local_sin_cos_theta"] {
        let inputs = rows(|g| g.dir().to_vec());
        case!("local_sin_cos_theta", inputs, |x| of_pair(local_sin_cos_theta(v3(x))));
    }
    geometry_azimuth_between ["azimuth_between"] {
        // Tangent, then projections that need not be unit: b equal to a, opposite, zero, along
        // the tangent, or independent.
        let inputs = rows(|g| {
            let (t, a) = (g.dir(), g.dir().map(|v| v * 3.0));
            let b = match g.below(6) {
                0 => a,
                1 => a.map(|v| -v),
                2 => [0.0; 3],
                3 => t,
                _ => g.dir(),
            };
            [t, a, b].concat()
        });
        case!("azimuth_between", inputs, |x| {
            vec![azimuth_between(v3(x), v3(&x[3..]), v3(&x[6..]))]
        });
    }
    geometry_fibre_angles ["fibre_angles"] {
        // Tangent +X or any; wi sometimes along the tangent.
        let inputs = rows(|g| {
            let t = if g.below(3) == 0 { [1.0, 0.0, 0.0] } else { g.dir() };
            let w = g.pair();
            [&t[..], if g.below(4) == 0 { &t[..] } else { &w[..3] }, &w[3..]].concat()
        });
        case!("fibre_angles", inputs, |x| {
            of_angles(fibre_angles(v3(x), v3(&x[3..]), v3(&x[6..])))
        });
    }
    geometry_local_fibre_angles ["local_fibre_angles"] {
        case!("local_fibre_angles", rows(|g| g.pair()), |x| {
            of_angles(local_fibre_angles(v3(x), v3(&x[3..])))
        });
    }
    geometry_fibre_frame ["fibre_frame", "local_directions"] {
        // Tangents of any length and sign, the poles (z = +-1, and -0) and the plane z = 0.
        let poles = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [0.3, -0.2, -0.0], [1.0, 0.0, 0.0]];
        let inputs = rows(|g| {
            let t = match g.below(3) {
                0 => poles[g.below(4)].to_vec(),
                _ => g.dir().iter().map(|c| c * 3.5).collect(),
            };
            [&t[..], &g.pair()[..]].concat()
        });
        case!("fibre_frame", inputs.clone(), |x| {
            fibre_frame(v3(x)).iter().flat_map(|v| of_v3(*v)).collect()
        });
        case!("local_directions", inputs, |x| {
            let [wi, wo] = local_directions(v3(x), v3(&x[3..]), v3(&x[6..]));
            [of_v3(wi), of_v3(wo)].concat()
        });
    }
    geometry_local_direction ["local_direction"] {
        let inputs = rows(|g| [&g.sin_cos()[..], &[g.pick(&ANGLE)]].concat());
        case!("local_direction", inputs, |x| of_v3(local_direction(x[0], x[1], x[2])));
    }

    fresnel_dielectric_ ["fresnel_dielectric"] {
        let inputs = scalars(&[SIN, ETA]);
        case!("fresnel_dielectric", inputs, |x| vec![fresnel_dielectric(x[0], x[1])]);
    }
    fresnel_from_outside_ ["fresnel_from_outside"] {
        let inputs = scalars(&[UNIT, ETA]);
        case!("fresnel_from_outside", inputs, |x| {
            vec![fresnel_from_outside(x[0], x[1], recip(x[1]))]
        });
    }
    fresnel_of_cosines_ ["fresnel_of_cosines"] {
        let inputs = scalars(&[UNIT, ETA]);
        case!("fresnel_of_cosines", inputs, |x| {
            vec![fresnel_of_cosines(x[0], snell_cos_t(x[0], x[1]), x[1])]
        });
    }
    fresnel_schlick_ ["fresnel_schlick"] {
        let inputs = scalars(&[SIN, ETA]);
        case!("fresnel_schlick", inputs, |x| vec![fresnel_schlick(x[0], x[1])]);
    }
    fresnel_bravais ["bravais_eta_perpendicular", "bravais_eta_parallel"] {
        case!("bravais", scalars(&[ETA, SIN]), |x| {
            vec![bravais_eta_perpendicular(x[0], x[1]), bravais_eta_parallel(x[0], x[1])]
        });
    }

    absorption_segment_length ["segment_length"] {
        for path in [PathLength::Chord, PathLength::Marschner2003] {
            let inputs = scalars(&[UNIT, COS_THETA_T]);
            case!(format!("segment_length({path:?})"), inputs, |x| {
                vec![segment_length(x[0], recip(x[1]), path)]
            });
        }
    }
    absorption_segment_transmittance ["segment_transmittance"] {
        for path in [PathLength::Chord, PathLength::Marschner2003] {
            let inputs = scalars(&[SIGMA_A, UNIT, COS_THETA_T]);
            case!(format!("segment_transmittance({path:?})"), inputs, |x| {
                vec![segment_transmittance(x[0], x[1], x[2], path)]
            });
        }
    }

    bessel ["i0e_split", "i0e_split_reduced", "BesselForm::i0e_split", "log_i0e", "log_i0", "i0"] {
        case!("i0e_split", scalars(&[BESSEL_X]), |x| of_pair(i0e_split(x[0])));
        case!("i0e_split_reduced", scalars(&[BESSEL_X]), |x| of_pair(i0e_split_reduced(x[0])));
        for form in [BesselForm::Full, BesselForm::Reduced] {
            case!(format!("{form:?}.i0e_split"), scalars(&[BESSEL_X]), |x| {
                of_pair(form.i0e_split(x[0]))
            });
        }
        case!("log_i0e", scalars(&[BESSEL_X]), |x| vec![log_i0e(x[0]), log_i0(x[0])]);
        case!("i0", scalars(&[I0_X]), |x| vec![i0(x[0])]);
    }
    lobe_deon ["deon_lobe", "DeonLobe::new", "DeonLobe::eval", "DeonLobe::eval_with"] {
        let inputs = rows(|g| [&[g.pick(&VARIANCE)][..], &g.sin_cos(), &g.sin_cos()].concat());
        case!("deon_lobe", inputs.clone(), |x| {
            let lobe = DeonLobe::new(x[0]);
            vec![deon_lobe(x[0], x[1], x[2], x[3], x[4]), lobe.eval(x[1], x[2], x[3], x[4])]
        });
        case!("deon_lobe_reduced", inputs, |x| {
            let lobe = DeonLobe::new(x[0]);
            vec![lobe.eval_with(BesselForm::Reduced, x[1], x[2], x[3], x[4])]
        });
    }
    lobe_deon_sample ["deon_lobe_sample_cos_theta"] {
        let inputs = scalars(&[VARIANCE, U]);
        case!("deon_lobe_sample", inputs, |x| vec![deon_lobe_sample_cos_theta(x[0], x[1])]);
    }
    lobe_gaussian ["gaussian_lobe"] {
        case!("gaussian_lobe", scalars(&[BETA, ANGLE]), |x| vec![gaussian_lobe(x[0], x[1])]);
    }
    lobe_hg_gerard_printed ["hg_gerard_printed"] {
        let inputs = scalars(&[HG_G, SIN]);
        case!("hg_gerard_printed", inputs, |x| vec![hg_gerard_printed(x[0], x[1])]);
    }
    lobe_hg_circle_factor ["hg_circle_factor"] {
        // g over (-1, 1) with its ends, where |g| is clamped below 1.
        let g = arg(-1.0, 1.0, &[-1.0, 0.0, 0.752, 0.999_999, 1.0]);
        case!("hg_circle_factor", scalars(&[g]), |x| vec![hg_circle_factor(x[0])]);
    }
    lobe_henyey_greenstein ["HenyeyGreenstein::eval"] {
        // g is a per-lobe constant folded into the shader: one trace per g.
        for g in [-0.9, 0.0, 0.3, 0.752, 0.99] {
            let lobe = HenyeyGreenstein::new(g).unwrap();
            let name = format!("HenyeyGreenstein::eval(g = {g})");
            case!(name, scalars(&[SIN]), |x| vec![lobe.eval(x[0])]);
        }
    }

    azimuthal_attenuations ["attenuations_from_fresnel", "attenuations", "attenuations_at_offset"] {
        case!("attenuations_from_fresnel", scalars(&[UNIT, UNIT]), |x| {
            attenuations_from_fresnel(x[0], x[1]).to_vec()
        });
        case!("attenuations", scalars(&[UNIT, ETA, SIN, UNIT]), |x| {
            attenuations(x[0], x[1], x[2], x[3]).to_vec()
        });
        // The path model is a per-shader constant: one trace per variant.
        for path in [PathLength::Chord, PathLength::Marschner2003] {
            let name = format!("attenuations_at_offset({path:?})");
            case!(name, scalars(&[SIN, SIN, UNIT, ETA, SIGMA_A]), |x| {
                attenuations_at_offset(x[0], x[1], x[2], x[3], x[4], path).to_vec()
            });
        }
    }
    lut_axis_cell ["axis_cell"] {
        // Inside, at and beyond both ends of a 17-sample axis over [-1.5, 2.5].
        let inputs = scalars(&[arg(-3.0, 4.0, &[-1.5, 2.5, -3.0, 4.0, 0.5])]);
        case!("axis_cell", inputs, |x| {
            let (i0, f) = axis_cell(x[0], -1.5, 2.5, 17);
            vec![i0, f]
        });
    }
    azimuthal_exit_angle ["exit_angle", "refracted_offset", "exit_angle_of_offset"] {
        let inputs = scalars(&[LOBE, HALF_ANGLE, HALF_ANGLE]);
        case!("exit_angle", inputs, |x| vec![exit_angle(x[0], x[1], x[2])]);
        let inputs = rows(|g| [&[g.pick(&SIN), g.pick(&ETA)][..], &g.sin_cos()].concat());
        case!("refracted_offset", inputs, |x| vec![refracted_offset(x[0], x[1], x[2], x[3])]);
        case!("exit_angle_of_offset", scalars(&[LOBE, SIN, ETA, SIN]), |x| {
            vec![exit_angle_of_offset(x[0], x[1], x[2], x[3])]
        });
    }
    azimuthal_path [
        "Refraction::new", "Refraction::sin_gamma_t", "Refraction::path",
        "FibrePath::transmittance", "FibrePath::attenuations"
    ] {
        // Inclination (sin, cos), eta, offset, sigma_a; one trace per path-length model.
        for length in [PathLength::Chord, PathLength::Marschner2003] {
            let inputs = rows(|g| {
                [&g.sin_cos()[..], &[g.pick(&ETA), g.pick(&SIN), g.pick(&SIGMA_A)]].concat()
            });
            case!(format!("Refraction::path({length:?})"), inputs, |x| {
                let r = Refraction::new(x[0], x[1], x[2], recip(x[2]));
                let p: FibrePath<_> = r.path(x[3], length);
                [
                    vec![r.sin_gamma_t(x[3]), p.gamma_o, p.gamma_t, p.segment_length, p.fresnel],
                    vec![p.transmittance(x[4])],
                    p.attenuations(x[4]).to_vec(),
                ]
                .concat()
            });
        }
    }
    azimuthal_trimmed_logistic [
        "TrimmedLogistic::new", "TrimmedLogistic::density", "TrimmedLogistic::densities",
        "TrimmedLogistic::sample"
    ] {
        case!("TrimmedLogistic", scalars(&[SCALE, ANGLE, ANGLE, ANGLE, U]), |x| {
            let d = TrimmedLogistic::new(x[0]);
            [
                vec![d.density(x[1]), d.sample(x[4])],
                d.densities([x[1], x[2], x[3]]).to_vec(),
            ]
            .concat()
        });
    }
    azimuthal_logistic ["logistic", "logistic_cdf", "trimmed_logistic", "trimmed_mass", "sample_trimmed_logistic"] {
        case!("logistic", scalars(&[ANGLE, SCALE]), |x| {
            vec![logistic(x[0], x[1]), logistic_cdf(x[0], x[1]), trimmed_logistic(x[0], x[1]), trimmed_mass(x[1])]
        });
        let inputs = scalars(&[U, SCALE]);
        case!("sample_trimmed_logistic", inputs, |x| vec![sample_trimmed_logistic(x[0], x[1])]);
    }
    azimuthal_wrapped_gaussian ["wrapped_gaussian", "sample_wrapped_gaussian"] {
        let inputs = scalars(&[ANGLE, BETA]);
        case!("wrapped_gaussian", inputs, |x| vec![wrapped_gaussian(x[0], x[1])]);
        case!("sample_wrapped_gaussian", scalars(&[U, U, BETA]), |x| {
            vec![sample_wrapped_gaussian(x[0], x[1], x[2])]
        });
    }

    chiang_new ["ChiangHair::new", "ChiangHair::uniforms"] {
        // The constructor folds a material to uniforms: one trace without inputs per material.
        for (k, &m) in MATERIALS.iter().enumerate() {
            case!(format!("ChiangHair::new(MATERIALS[{k}])"), vec![vec![]], |_x| {
                ChiangHair::new(&params(m)).uniforms().to_values()
            });
        }
    }
    chiang_uniforms [
        "ChiangHair::from_uniforms", "ChiangHair::eta", "ChiangHair::lobe_names",
        "ChiangHair::uses_offset", "ChiangHair::with_uniforms", "UniformValue::push_to",
        "UniformValue::take_from", "AtOffset::cast"
    ] {
        let model = ChiangHair::new(&HairParams::default());
        model_case!("ChiangHair::from_uniforms", model, vec![], ResultType::Scalars, rows(|g| g.hair()), |m, _x| {
            let flags = [m.lobe_names().len() as f64, f64::from(u8::from(m.uses_offset()))];
            [m.uniforms().to_values(), vec![m.eta()], consts(&flags)].concat()
        });
    }
    chiang_eval [
        "ChiangHair::eval", "LobeTerms::value", "PairAngles::of", "query_of", "Query::new",
        "AtOffset::lobe_terms"
    ] {
        // Through the library's own shader entry point: (uniforms, wi, wo, h) -> vec3.
        let model = ChiangHair::new(&HairParams::default());
        let graph = trace_eval(&model);
        let wgsl = graph.to_wgsl("chiang_eval");
        assert!(
            wgsl.contains("struct ChiangUniforms {")
                && wgsl.contains("fn chiang_eval(uniforms: ChiangUniforms, wi: vec3<f32>, wo: vec3<f32>, h: f32) -> vec3<f32>")
                && wgsl.contains("uniforms.logistic_norm")
                && wgsl.contains("uniforms.sigma_a.z"),
            "{wgsl}"
        );
        check("ChiangHair::eval", &chiang_rows(), &graph, |row| {
            let w = mat();
            let m = model.with_uniforms::<f32>(UniformBlock::from_values(&row[..w]));
            m.eval(&query_of(&row[w..])).to_vec()
        });
        // The inputs of the library's helper are the uniforms then the query.
        let q = [0.0, 1.0, 0.0, 0.0, 0.6, 0.8, 0.1];
        let cpu = model.instantiate::<f32>().eval(&query_of(&q));
        assert_eq!(graph.eval_f32(&traced_inputs(&model, &q)), cpu.to_vec());
    }
    chiang_eval_lobes ["ChiangHair::eval_lobes", "LobeTerms::per_lobe"] {
        let model = ChiangHair::new(&HairParams::default());
        model_case!("ChiangHair::eval_lobes", model, query_parameters(true), ResultType::Scalars, chiang_rows(), |m, x| {
            m.eval_lobes(&query_of(x)).concat()
        });
    }
    chiang_pdf ["ChiangHair::pdf", "LobeTerms::pdf"] {
        let model = ChiangHair::new(&HairParams::default());
        model_case!("ChiangHair::pdf", model, query_parameters(true), ResultType::Scalars, chiang_rows(), |m, x| {
            vec![m.pdf(&query_of(x))]
        });
    }
    chiang_sample ["ChiangHair::sample", "AtOffset::sample_offset"] {
        // Uniforms, wo, h, then the four numbers.
        let inputs = rows(|g| [&g.hair()[..], &g.dir(), &[g.pick(&SIN)], &g.numbers()].concat());
        let model = ChiangHair::new(&HairParams::default());
        model_case!("ChiangHair::sample", model, sample_parameters(), ResultType::Scalars, inputs, |m, x| {
            let s = m.sample(v3(x), x[3], numbers(&x[4..]));
            [of_v3(s.wi), s.value.to_vec(), vec![s.pdf]].concat()
        });
    }

    far_field [
        "ChiangHair::with_rule", "ChiangHair::near_field", "ChiangHair::azimuthal",
        "ChiangHair::offsets", "OffsetNodes::new", "OffsetNodes::lobe_terms", "OffsetNodes::cast",
        "Query::far"
    ] {
        // The rule's nodes are folded into the shader as constants: one trace per node count
        // (1 node and a small rule keep the WGSL short; the loop is the same for more).
        for nodes in [1, 4] {
            let rule = FarFieldRule::gauss_legendre(nodes).unwrap();
            let model = ChiangFarField::with_rule(&HairParams::default(), &rule);
            assert!(trace_eval(&model).to_wgsl("far").contains("wo: vec3<f32>) -> vec3<f32>"));
            let name = format!("ChiangFarField::eval({nodes} nodes)");
            model_case!(name, model, query_parameters(false), ResultType::Scalars, rows(|g| [g.hair(), g.pair()].concat()), |ff, x| {
                let q = Query::far(v3(x), v3(&x[3..]));
                let a = local_fibre_angles(q.wi, q.wo);
                let (an, wn) = ff.azimuthal(a.sin_theta_o, a.cos_theta_o, a.phi);
                let flags = [ff.lobe_names().len() as f64, f64::from(u8::from(ff.uses_offset()))];
                [
                    ff.eval(&q).to_vec(),
                    ff.eval_lobes(&q).concat(),
                    vec![ff.pdf(&q), ff.near_field().eta()],
                    an.concat(),
                    wn.to_vec(),
                    consts(&flags),
                ]
                .concat()
            });
        }
        // The constructor in f32 is the f64 model rounded: the same bits as `instantiate`.
        let rule = FarFieldRule::gauss_legendre(4).unwrap();
        let q = Query::far(V3::from_f64(0.0, 1.0, 0.0), V3::from_f64(0.6, 0.0, 0.8));
        let direct = ChiangFarField::<f32>::with_rule(&HairParams::default(), &rule).eval(&q);
        let rounded = ChiangFarField::with_rule(&HairParams::default(), &rule).instantiate::<f32>().eval(&q);
        assert_eq!(direct, rounded);
    }
    far_field_sample ["OffsetNodes::sample_offset"] {
        // Uniforms, wo, h (ignored), then the four numbers (the last picks the offset node).
        for nodes in [1, 4] {
            let rule = FarFieldRule::gauss_legendre(nodes).unwrap();
            let inputs = rows(|g| [&g.hair()[..], &g.dir(), &[g.pick(&SIN)], &g.numbers()].concat());
            let model = ChiangFarField::with_rule(&HairParams::default(), &rule);
            let name = format!("ChiangFarField::sample({nodes} nodes)");
            model_case!(name, model, sample_parameters(), ResultType::Scalars, inputs, |ff, x| {
                let s = ff.sample(v3(x), x[3], numbers(&x[4..]));
                [of_v3(s.wi), s.value.to_vec(), vec![s.pdf]].concat()
            });
        }
    }

    sh_eval_sh ["eval_sh"] {
        // The band count is the const parameter N = bands^2: one trace per band count.
        case!("eval_sh(bands = 1)", sh_direction_rows(), |x| {
            eval_sh::<_, 1>(x[0], x[1], x[2]).to_vec()
        });
        case!("eval_sh(bands = 3)", sh_direction_rows(), |x| {
            eval_sh::<_, 9>(x[0], x[1], x[2]).to_vec()
        });
        case!("eval_sh(bands = 6)", sh_direction_rows(), |x| {
            eval_sh::<_, 36>(x[0], x[1], x[2]).to_vec()
        });
        case!("eval_sh(bands = 10)", sh_direction_rows(), |x| {
            eval_sh::<_, 100>(x[0], x[1], x[2]).to_vec()
        });
    }
    sh_eval_sh_into ["eval_sh_into"] {
        // `out` two entries longer than needed: the tail must be left as it was (the input x).
        for bands in [1, 3, 6, 10] {
            case!(format!("eval_sh_into(bands = {bands})"), sh_direction_rows(), |x| {
                let mut out = vec![x[0]; bands * bands + 2];
                eval_sh_into(bands, x[0], x[1], x[2], &mut out).unwrap();
                out
            });
        }
    }
    sh_rotate_zonal_into ["rotate_zonal_into"] {
        // Zonal coefficients, then the direction +z is rotated to.
        for bands in [1, 3, 6] {
            let first = SH_DIRECTIONS.iter().map(|d| [vec![1.0; bands], d.to_vec()].concat());
            let inputs = listed_then(first.collect(), |g| {
                [g.coefficients(bands), g.sphere().to_vec()].concat()
            });
            case!(format!("rotate_zonal_into(bands = {bands})"), inputs, |x| {
                let mut out = vec![x[0]; bands * bands];
                rotate_zonal_into(&x[..bands], x[bands], x[bands + 1], x[bands + 2], &mut out)
                    .unwrap();
                out
            });
        }
    }
    sh_rotate_band1 ["rotate_band1"] {
        case!("rotate_band1", rotation_rows(3), |x| {
            rotate_band1(&mat3(x), arr(&x[9..])).to_vec()
        });
    }
    sh_rotate_band2 ["rotate_band2"] {
        case!("rotate_band2", rotation_rows(5), |x| {
            rotate_band2(&mat3(x), arr(&x[9..])).to_vec()
        });
    }
    sh_rotation_blocks ["rotation_blocks", "rotate_with_blocks"] {
        for bands in [1, 3, 5] {
            let n = bands * bands;
            case!(format!("rotation_blocks(lmax = {})", bands - 1), rotation_rows(n), |x| {
                let blocks = rotation_blocks(&mat3(x), bands - 1);
                let mut out = vec![x[0]; n];
                rotate_with_blocks(&blocks, &x[9..9 + n], &mut out);
                out
            });
        }
    }
    sh_rotate_bands012 ["rotate_bands012"] {
        case!("rotate_bands012", rotation_rows(9), |x| {
            rotate_bands012(&mat3(x), arr(&x[9..])).to_vec()
        });
    }
    sh_product_plan ["ProductPlan::apply", "ProductPlan::apply_into", "ProductPlan::triple"] {
        // The plan is built outside the trace (it is f64 set-up); its coefficients are folded
        // into the shader as constants.
        for n_bands in [2, 4] {
            let (plan, n) = (ProductPlan::new(n_bands).unwrap(), n_bands * n_bands);
            let inputs = rows(|g| g.coefficient_pair(n));
            case!(format!("ProductPlan::apply(n_bands = {n_bands})"), inputs.clone(), |x| {
                plan.apply(&x[..n], &x[n..]).unwrap()
            });
            case!(format!("ProductPlan::apply_into(n_bands = {n_bands})"), inputs, |x| {
                let mut out = vec![x[0]; n];
                plan.apply_into(&x[..n], &x[n..], &mut out).unwrap();
                out
            });
            let inputs = rows(|g| [g.coefficient_pair(n), g.coefficients(n)].concat());
            case!(format!("ProductPlan::triple(n_bands = {n_bands})"), inputs, |x| {
                vec![plan.triple(&x[..n], &x[n..2 * n], &x[2 * n..]).unwrap()]
            });
        }
    }
    sh_product ["product", "triple_product_integral"] {
        for n_bands in [2, 4] {
            let n = n_bands * n_bands;
            let inputs = rows(|g| g.coefficient_pair(n));
            case!(format!("product(n_bands = {n_bands})"), inputs, |x| {
                product(n_bands, &x[..n], &x[n..]).unwrap()
            });
            let inputs = rows(|g| [g.coefficient_pair(n), g.coefficients(n)].concat());
            case!(format!("triple_product_integral(n_bands = {n_bands})"), inputs, |x| {
                vec![triple_product_integral(n_bands, &x[..n], &x[n..2 * n], &x[2 * n..]).unwrap()]
            });
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Coverage.

/// The public functions generic over [`Real`] in `src/`, found by parsing every file with `syn`
/// (so the result does not depend on how the source is formatted).
///
/// Reported: a free function or inherent method with `pub` visibility (not `pub(crate)`) that
/// has a type parameter bounded by `Real` (in its own generics or where clause, or in those of
/// its `impl` block), and every method of a trait implementation whose `impl` block has such a
/// parameter (the trait's methods are public with the trait). Names are `Type::method` for
/// methods (the implementing type, also for trait implementations) and the bare name otherwise.
/// Items under `#[cfg(test)]` are skipped; functions generated by macros are not seen.
fn scan_public_generic_functions() -> BTreeSet<String> {
    use syn::visit::Visit;

    fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                rust_files(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    /// Whether `generics` has a type parameter bounded by `Real`.
    fn bounds_real(generics: &syn::Generics) -> bool {
        let is_real = |bound: &syn::TypeParamBound| match bound {
            syn::TypeParamBound::Trait(t) => {
                t.path.segments.last().is_some_and(|s| s.ident == "Real")
            }
            _ => false,
        };
        let in_params = generics.type_params().any(|p| p.bounds.iter().any(is_real));
        let in_where = generics.where_clause.as_ref().is_some_and(|w| {
            w.predicates.iter().any(|p| match p {
                syn::WherePredicate::Type(t) => t.bounds.iter().any(is_real),
                _ => false,
            })
        });
        in_params || in_where
    }
    fn is_test_only(attrs: &[syn::Attribute]) -> bool {
        attrs.iter().any(|a| {
            a.path().is_ident("cfg") && a.meta.to_token_stream().to_string().contains("test")
        })
    }
    fn type_name(ty: &syn::Type) -> String {
        match ty {
            syn::Type::Path(p) => p
                .path
                .segments
                .last()
                .map(|s| s.ident.to_string())
                .unwrap_or_default(),
            other => other.to_token_stream().to_string(),
        }
    }
    use quote::ToTokens;
    #[derive(Default)]
    struct Scan(BTreeSet<String>);
    impl<'a> Visit<'a> for Scan {
        fn visit_item_mod(&mut self, m: &'a syn::ItemMod) {
            if !is_test_only(&m.attrs) {
                syn::visit::visit_item_mod(self, m);
            }
        }
        fn visit_item_fn(&mut self, f: &'a syn::ItemFn) {
            let public = matches!(f.vis, syn::Visibility::Public(_));
            if public && !is_test_only(&f.attrs) && bounds_real(&f.sig.generics) {
                self.0.insert(f.sig.ident.to_string());
            }
        }
        fn visit_item_impl(&mut self, i: &'a syn::ItemImpl) {
            if is_test_only(&i.attrs) {
                return;
            }
            // A trait implemented for a type parameter or an array (`impl<R: Real> Trait for
            // R`) is named after the trait.
            let parameters: Vec<String> = i
                .generics
                .type_params()
                .map(|p| p.ident.to_string())
                .collect();
            let mut ty = type_name(&i.self_ty);
            if let Some((_, path, _)) = &i.trait_ {
                if parameters.contains(&ty) || matches!(*i.self_ty, syn::Type::Array(_)) {
                    ty = path
                        .segments
                        .last()
                        .map(|s| s.ident.to_string())
                        .unwrap_or_default();
                }
            }
            let generic_impl = bounds_real(&i.generics);
            for item in &i.items {
                if let syn::ImplItem::Fn(f) = item {
                    let public = i.trait_.is_some() || matches!(f.vis, syn::Visibility::Public(_));
                    if public && (generic_impl || bounds_real(&f.sig.generics)) {
                        self.0.insert(format!("{ty}::{}", f.sig.ident));
                    }
                }
            }
        }
    }
    let mut files = Vec::new();
    rust_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut files,
    );
    let mut scan = Scan::default();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        let ast = syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        scan.visit_file(&ast);
    }
    scan.0
}

#[test]
fn coverage_matches_the_source() {
    let all: Vec<&str> = [
        COVERED,
        models::COVERED,
        tables::COVERED,
        classic::COVERED,
        unreal::COVERED,
        frostbite::COVERED,
        composed::COVERED,
        varying::COVERED,
        strands::COVERED,
        gerard_sh::COVERED,
    ]
    .concat();
    let covered: BTreeSet<String> = all.iter().map(|s| s.to_string()).collect();
    assert_eq!(covered.len(), all.len(), "a function is listed twice");
    let public = scan_public_generic_functions();
    let untested: Vec<_> = public.difference(&covered).collect();
    let stale: Vec<_> = covered.difference(&public).collect();
    assert!(
        untested.is_empty() && stale.is_empty(),
        "public generic functions without a trace test: {untested:?}; \
         listed as traced but not found in src/: {stale:?}"
    );
}

/// Regression: `f32::max` leaves the sign of a zero result unspecified, and rustc at opt-level 3
/// folded `x.max(0.0)` with a constant operand differently from the interpreter's runtime
/// `max(a, b)` (for x = -0.0 the `f32` `safe_sqrt` gave +0.0, the graph -0.0). `Real::max` and
/// `Real::min` are now defined by one comparison, so both agree.
#[test]
fn signed_zero_through_max_is_reproduced() {
    case!("safe_sqrt", vec![vec![-0.0]], |x| vec![safe_sqrt(x[0])]);
}

#[test]
fn the_validator_rejects_bad_wgsl() {
    assert!(validate_wgsl("fn f(x0: f32) -> f32 {\n    return x0;\n}\n").is_ok());
    assert!(validate_wgsl("fn f(x0: f32) -> f32 {\n    return x1;\n}\n").is_err());
    assert!(validate_wgsl("fn f(x0: f32) -> f32 {\n    return x0 < 1.0f;\n}\n").is_err());
}

#[test]
fn the_scan_finds_known_functions() {
    // Guards the scan itself: a free function, a method of a generic impl, a generic method
    // of a plain impl, and a multi-line signature.
    let public = scan_public_generic_functions();
    for name in [
        "pi",
        "ChiangHair::eval",
        "HenyeyGreenstein::eval",
        "segment_transmittance",
    ] {
        assert!(public.contains(name), "{name} not found in {public:?}");
    }
    assert!(
        !public.contains("HenyeyGreenstein::new") && !public.contains("Absorption::from_color")
    );
}
