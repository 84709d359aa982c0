//! The shader form of every registered model, baked or with varying inputs
//! (`hairmath::registry::ShaderEntry`, `hairmath::bcsdf::trace_shader`).
//!
//! For every model with a shader form, at three parameter sets (brown, smooth blonde and rough
//! dark hair as the model maps them, the absorption given as sigma_a, melanin and a colour),
//! with no varying input, each varying input alone and all of them at once:
//!
//! - the traced graph interpreted in `f32` ([`Graph::eval_f32`]) at the given values is bit
//!   for bit the `f32` model reading the uniforms as the shader computes them
//!   (`CpuShader::shader`), on the hard direction pairs and 500 others;
//! - it is bit for bit the `f32` instantiation (`Model::instantiate`, the `f64` uniforms
//!   rounded once) where those uniforms are the same bits, which they are with no varying
//!   input and for every uniform that depends on no varying input;
//! - elsewhere (a uniform derived in `f32` differs from the rounded `f64` one: measured at
//!   most 5.2 ulps of its value, each formula's own rounding) it is within a tolerance of
//!   the propagated difference: `|traced - rounded| <= C_rel 2^-24 |rounded|` where the value
//!   is at least 1e-3 of its channel's largest over the directions (`peak`), and
//!   `<= C_peak 2^-24 peak` everywhere. The model amplifies a uniform's relative error `eps`
//!   by its sensitivity to it: `|x| eps` through a factor `e^x` (the absorption
//!   `exp(-sigma_a l)` with `sigma_a l` of tens for dark hair, d'Eon's and the
//!   Gaussians' exponents), `eps Phi / s` through a logistic of scale s about the exit angle
//!   Phi (Chiang's N_p: a one-ulp change of `1/eta` moves Phi), `sqrt(2 e |ln S|) eps` through
//!   a lobe `sin^e` whose axis moves (Scheuermann's shifted tangents, e up to 250), so that
//!   `C_rel` is tens to a few hundred ulps where the value is small against its peak, while
//!   the error against the peak (`C_peak`, bounded because `|x| e^x <= 1/e`) stays a few ulps
//!   except for the sharp strand lobes. [`TOLERANCE_ULPS`] lists both per model, about
//!   twice the largest values measured on 20,000 direction pairs (in its comments).
//!
//! Also: `uniforms_in::<f64>` of the values a model was built from is its `f64` uniforms
//! exactly; the signatures name the varying inputs in the given order; the errors of unknown,
//! baked and duplicate names, of an absorption form other than the given one, of `marschner`
//! and `chiang-far --reference`; and, by proptest, the traced shaders with every input varying
//! give finite non-negative values for random valid inputs and finite values for inputs
//! outside their domains (negative colours, roughness 0, huge sigma_a: the shader clamps).

use hairmath::absorption::Absorption;
use hairmath::bcsdf::{AbsorptionInput, InputKind, InputValue, InputValues, ShaderInputError};
use hairmath::params::{AzimuthalRoughness, HairParams, HairValues};
use hairmath::real::{ArgType, Graph};
use hairmath::registry::{find_model, ModelEntry, ShaderEntry, MODELS, WITHOUT_SHADER_FORM};
use proptest::prelude::*;
use std::f64::consts::PI;

/// The tolerance per model (module documentation): `(model, C_rel, C_peak)` in units of
/// [`ULP`], about twice the largest values measured on 20,000 direction pairs per
/// configuration (in the comments: `C_rel`, `C_peak`, and the largest difference of a derived
/// uniform from the rounded one in ulps of its value).
const TOLERANCE_ULPS: &[(&str, f64, f64)] = &[
    ("chiang", 300.0, 8.0),     // 143.2, 3.9; uniforms 5.2 (varying eta: 1 / eta)
    ("chiang-far", 50.0, 5.0),  // 24.3, 2.3; 5.2
    ("karis", 72.0, 8.0),       // 35.0, 3.7; 2.7
    ("karis-refit", 72.0, 8.0), // 35.7, 3.8; 5.2
    ("kajiya-kay", 0.0, 0.0),   // the uniforms are the inputs: bit for bit
    ("tressfx", 4.0, 3.0),      // 1.9, 1.4; 1.2 (cos and sin of the shifts)
    ("scheuermann", 240.0, 180.0), // 115.9, 89.0; 1.8 (the shifted tangents)
    ("nguyen-donnelly", 0.0, 0.0), // nothing varies
    ("gerard", 10.0, 6.0),      // 4.6, 3.0; 2.7
    ("frostbite", 60.0, 6.0),   // 29.6, 3.0; 5.2
    ("frostbite-refit", 60.0, 6.0), // 25.5, 2.8; 5.2
];

/// Values below this fraction of their channel's peak are held to the peak-relative bound
/// only.
const RELATIVE_FLOOR: f32 = 1e-3;

/// One ulp of `f32` at 1, 2^-24 (half of `f32::EPSILON`).
const ULP: f64 = f32::EPSILON as f64 / 2.0;

/// The difference of the traced value `traced` from the rounded model's `value`, in units
/// of [`ULP`]: relative to the value where it is at least [`RELATIVE_FLOOR`] of the channel's
/// `peak` (else 0), and relative to the peak.
fn ulps(traced: f32, value: f32, peak: f32) -> (f64, f64) {
    let diff = f64::from((traced - value).abs());
    if diff == 0.0 {
        return (0.0, 0.0);
    }
    let rel = match value.abs() >= RELATIVE_FLOOR * peak {
        true => diff / (ULP * f64::from(value.abs())),
        false => 0.0,
    };
    (rel, diff / (ULP * f64::from(peak)))
}

/// `(C_rel, C_peak)` of `model`.
fn tolerance(model: &str) -> (f64, f64) {
    TOLERANCE_ULPS
        .iter()
        .find(|(m, ..)| *m == model)
        .map_or((0.0, 0.0), |&(_, r, p)| (r, p))
}

/// The physical hairs of the three parameter sets and how their absorption is given.
fn hairs() -> [(&'static str, HairParams, Option<AbsorptionInput>); 3] {
    let hair = |beta_m, beta_n, alpha_deg: f64, eta, eu: f64, pheo: f64| {
        HairParams::try_from(HairValues {
            beta_m,
            beta_n,
            alpha: alpha_deg.to_radians(),
            eta,
            sigma_a: Absorption::from_melanin(eu, pheo).unwrap().rgb(),
        })
        .unwrap()
    };
    let blonde = hair(0.15, 0.2, -1.0, 1.6, 0.3, 0.1);
    let dark = hair(0.6, 0.7, 3.0, 1.5, 4.0, 0.5);
    let dark_colour = dark.sigma_a.to_color(AzimuthalRoughness::new(0.3).unwrap());
    let brown = HairParams::default();
    [
        (
            "brown",
            brown,
            Some(AbsorptionInput::SigmaA(brown.sigma_a.rgb())),
        ),
        (
            "blonde",
            blonde,
            Some(AbsorptionInput::Melanin {
                eumelanin: 0.3,
                pheomelanin: 0.1,
            }),
        ),
        ("dark", dark, Some(AbsorptionInput::Color(dark_colour))),
    ]
}

/// The values of `hair` for `entry`: the approximation's mapping, or the reference's inputs
/// themselves (the far field with `nodes` nodes); the absorption replaced by `absorption`.
fn values_of(
    entry: &ModelEntry,
    hair: &HairParams,
    absorption: Option<AbsorptionInput>,
    nodes: usize,
) -> InputValues {
    let mut values = match entry.approximation {
        Some(a) => (a.mapped_inputs)(hair),
        None => {
            let mut v = InputValues::new();
            v.set("beta_m", InputValue::Number(hair.beta_m.get()));
            v.set("beta_n", InputValue::Number(hair.beta_n.get()));
            v.set("alpha", InputValue::Number(hair.alpha.get()));
            v.set("eta", InputValue::Number(hair.eta.get()));
            let sigma_a = AbsorptionInput::SigmaA(hair.sigma_a.rgb());
            v.set("sigma_a", InputValue::Absorption(sigma_a));
            if entry.inputs.iter().any(|i| i.name == "nodes") {
                v.set("nodes", InputValue::Count(nodes));
            }
            v
        }
    };
    let has_absorption = entry.inputs.iter().any(|i| i.kind == InputKind::Absorption);
    if let (Some(a), true) = (absorption, has_absorption) {
        values.set("sigma_a", InputValue::Absorption(a));
    }
    values
}

/// The registered models with a shader form.
fn traced_models() -> Vec<(&'static ModelEntry, &'static ShaderEntry)> {
    MODELS
        .iter()
        .filter_map(|m| m.shader.as_ref().map(|s| (m, s)))
        .collect()
}

/// A splitmix64 stream.
struct Gen(u64);

impl Gen {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A unit direction uniform on the sphere.
    fn dir(&mut self) -> [f64; 3] {
        let z = 2.0 * self.uniform() - 1.0;
        let phi = 2.0 * PI * self.uniform();
        let s = (1.0 - z * z).sqrt();
        [z, s * phi.cos(), s * phi.sin()]
    }
}

/// Uniform direction pairs per configuration (after the hard ones).
const PAIRS: usize = 500;

/// Direction pairs (and h): along the tangent, grazing from opposite ends, phi = 0 and pi,
/// wi = -wo, then 60 uniform pairs.
fn queries(near_field: bool) -> Vec<Vec<f32>> {
    let hard: &[[f64; 6]] = &[
        [1.0, 0.0, 0.0, -1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0, 0.6, 0.8],
        [0.999_999_9, 4.47e-4, 0.0, -0.999_999_9, 0.0, 4.47e-4],
        [0.0, 1.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 1.0, 0.0, 0.0, -1.0, 0.0],
        [-0.3, 0.0, 0.953_939_2, 0.3, 0.0, -0.953_939_2],
    ];
    let mut g = Gen(0x5eed);
    let mut out: Vec<Vec<f64>> = hard.iter().map(|p| p.to_vec()).collect();
    out.extend((0..PAIRS).map(|_| [g.dir(), g.dir()].concat()));
    out.iter_mut().enumerate().for_each(|(k, q)| {
        if near_field {
            q.push([0.0, 0.5, -0.9, 1.0, -1.0][k % 5]);
        }
    });
    out.iter()
        .map(|q| q.iter().map(|&v| v as f32).collect())
        .collect()
}

/// The varying inputs to test for `values`: none, each alone, all.
fn configurations(shader: &ShaderEntry, values: &InputValues) -> Vec<Vec<&'static str>> {
    let names = (shader.varying)(values);
    let mut out = vec![Vec::new()];
    out.extend(names.iter().map(|n| vec![*n]));
    if names.len() > 1 {
        out.push(names.clone());
    }
    out
}

/// Checks one configuration; returns the largest measured `(C_rel, C_peak)` (0 where every
/// difference is bit for bit) and the largest difference of a uniform in ulps of its value.
fn check_configuration(
    entry: &ModelEntry,
    shader: &ShaderEntry,
    values: &InputValues,
    varying: &[&str],
    label: &str,
) -> (f64, f64, f64) {
    let graph = (shader.trace)(values, varying).unwrap_or_else(|e| panic!("{label}: {e}"));
    let cpu = (shader.cpu)(values, varying, None).unwrap();
    assert_eq!(
        cpu.uniforms_in_f64, cpu.uniforms_f64,
        "{label}: one derivation"
    );
    let near = (entry.build)(values).unwrap().uses_offset();
    check_signature(&graph, near, varying, label);
    let same_uniforms = cpu
        .shader_uniforms
        .iter()
        .zip(&cpu.rounded_uniforms)
        .all(|(a, b)| a.to_bits() == b.to_bits());
    if varying.is_empty() {
        assert!(
            same_uniforms,
            "{label}: the baked shader reads the rounded uniforms"
        );
    }
    // How far the uniforms the shader derives in f32 are from the rounded f64 ones, in ulps
    // of the value.
    let uniform_ulps = cpu
        .shader_uniforms
        .iter()
        .zip(&cpu.rounded_uniforms)
        .map(|(a, b)| match a == b {
            true => 0.0,
            false => f64::from((a - b).abs()) / (ULP * f64::from(b.abs()).max(1e-30)),
        })
        .fold(0.0, f64::max);
    let queries = queries(near);
    let rounded: Vec<[f32; 3]> = queries
        .iter()
        .map(|q| cpu.rounded.eval(&query(q)))
        .collect();
    let peak: Vec<f32> = (0..3)
        .map(|c| rounded.iter().map(|v| v[c].abs()).fold(0.0, f32::max))
        .collect();
    let (tol_rel, tol_peak) = tolerance(entry.name);
    let mut worst = (0.0_f64, 0.0_f64, uniform_ulps);
    for (q, r) in queries.iter().zip(&rounded) {
        let inputs = [&q[..], &cpu.arguments].concat();
        let traced = graph.eval_f32(&inputs);
        let shaded = cpu.shader.eval(&query(q));
        for c in 0..3 {
            assert_eq!(
                traced[c].to_bits(),
                shaded[c].to_bits(),
                "{label}: the graph against the CPU shader at {q:?}: {traced:?} vs {shaded:?}"
            );
            if same_uniforms {
                assert_eq!(
                    traced[c].to_bits(),
                    r[c].to_bits(),
                    "{label}: the graph against the rounded model at {q:?}"
                );
            } else {
                let (rel, of_peak) = ulps(traced[c], r[c], peak[c]);
                worst = (worst.0.max(rel), worst.1.max(of_peak), worst.2);
                assert!(
                    rel <= tol_rel && of_peak <= tol_peak,
                    "{label}: channel {c} at {q:?}: {} vs {} ({rel:.1} ulps of the value, \
                     {of_peak:.1} of the peak {})",
                    traced[c],
                    r[c],
                    peak[c]
                );
            }
        }
    }
    worst
}

/// The query of a row (wi, wo[, h]).
fn query(q: &[f32]) -> hairmath::bcsdf::Query<f32> {
    hairmath::bcsdf::query_of(q)
}

/// The graph's arguments are wi, wo[, h], then the varying inputs in the given order (each
/// `vec3<f32>` or `f32` as its kind), and the WGSL names them.
fn check_signature(graph: &Graph, near: bool, varying: &[&str], label: &str) {
    let arguments: Vec<(&str, &ArgType)> = graph
        .signature()
        .parameters
        .iter()
        .filter(|p| p.constant.is_none())
        .map(|p| (p.name.as_str(), &p.ty))
        .collect();
    let mut expected = vec!["wi", "wo"];
    if near {
        expected.push("h");
    }
    expected.extend_from_slice(varying);
    let names: Vec<&str> = arguments.iter().map(|(n, _)| *n).collect();
    assert_eq!(names, expected, "{label}");
    for (name, ty) in &arguments[expected.len() - varying.len()..] {
        let vector = matches!(*name, "sigma_a" | "color" | "kd") || name.starts_with("ks");
        let want = if vector {
            ArgType::Vec3
        } else {
            ArgType::Scalar
        };
        assert_eq!(**ty, want, "{label}: {name}");
    }
    let wgsl = graph.to_wgsl("hair_bcsdf");
    let mut header = String::from("fn hair_bcsdf(");
    if varying.is_empty() {
        header.push_str("wi: vec3<f32>");
    } else {
        let typed: Vec<String> = arguments
            .iter()
            .map(|(n, t)| {
                let t = if **t == ArgType::Vec3 {
                    "vec3<f32>"
                } else {
                    "f32"
                };
                format!("{n}: {t}")
            })
            .collect();
        header.push_str(&typed.join(", "));
        header.push_str(") -> vec3<f32>");
    }
    assert!(wgsl.contains(&header), "{label}: {header} in\n{wgsl}");
}

#[test]
fn every_shader_computes_what_the_cpu_computes() {
    let mut report = Vec::new();
    for (entry, shader) in traced_models() {
        let mut worst = (0.0_f64, 0.0_f64, 0.0_f64);
        for (k, (hair_name, hair, absorption)) in hairs().into_iter().enumerate() {
            let nodes = [64, 16, 8][k];
            let values = values_of(entry, &hair, absorption, nodes);
            for varying in configurations(shader, &values) {
                let label = format!("{} ({hair_name}) varying {varying:?}", entry.name);
                let w = check_configuration(entry, shader, &values, &varying, &label);
                worst = (worst.0.max(w.0), worst.1.max(w.1), worst.2.max(w.2));
            }
        }
        report.push(format!(
            "{}: {:.1}, {:.1} (uniforms {:.1})",
            entry.name, worst.0, worst.1, worst.2
        ));
    }
    eprintln!("measured (C_rel, C_peak) per model: {}", report.join("; "));
}

#[test]
fn every_model_has_a_shader_form_or_a_reason() {
    for entry in MODELS {
        match &entry.shader {
            Some(shader) => {
                // The varying names are inputs of the model (or absorption forms), of kinds
                // that can vary.
                let values = values_of(entry, &HairParams::default(), None, 8);
                for name in (shader.varying)(&values) {
                    let input = entry.inputs.iter().find(|i| i.name == name);
                    let form = ["color", "eumelanin", "pheomelanin"].contains(&name);
                    assert!(
                        form || input.is_some_and(|i| matches!(
                            i.kind,
                            InputKind::Number
                                | InputKind::Angle
                                | InputKind::Rgb
                                | InputKind::Absorption
                        )),
                        "{}: {name}",
                        entry.name
                    );
                }
            }
            None => assert!(
                WITHOUT_SHADER_FORM.iter().any(|(n, _)| *n == entry.name),
                "{} has no shader form and no reason",
                entry.name
            ),
        }
    }
    let marschner = find_model("marschner").unwrap();
    let mut values = InputValues::new();
    values.set("alpha_r", InputValue::Number(-0.087));
    values.set("beta_r", InputValue::Number(0.13));
    values.set("eta", InputValue::Number(1.55));
    values.set(
        "sigma_a",
        InputValue::Absorption(AbsorptionInput::SigmaA([0.5; 3])),
    );
    let e = marschner.trace_shader(&values, &[]).unwrap_err();
    assert!(matches!(
        e,
        ShaderInputError::NoShaderForm {
            model: "marschner",
            ..
        }
    ));
    assert!(e.to_string().contains("root"), "{e}");
}

#[test]
fn names_that_cannot_vary_are_errors_that_say_why() {
    let chiang = find_model("chiang").unwrap();
    let far = find_model("chiang-far").unwrap();
    let values = values_of(chiang, &HairParams::default(), None, 8);
    let fail = |entry: &ModelEntry, values: &InputValues, varying: &[&str]| {
        entry.trace_shader(values, varying).unwrap_err()
    };
    // Unknown: the model's inputs are listed.
    let e = fail(chiang, &values, &["roughness"]);
    assert!(matches!(e, ShaderInputError::Unknown { .. }), "{e:?}");
    assert!(
        e.to_string()
            .contains("beta_m, beta_n, alpha, eta, sigma_a"),
        "{e}"
    );
    // Twice.
    let e = fail(chiang, &values, &["beta_m", "eta", "beta_m"]);
    assert_eq!(
        e,
        ShaderInputError::Duplicate {
            name: "beta_m".into()
        }
    );
    // The absorption was given as sigma_a: it cannot vary as a colour.
    let e = fail(chiang, &values, &["color"]);
    assert!(
        matches!(e, ShaderInputError::AbsorptionForm { .. }),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("--sigma-a") && e.to_string().contains("as sigma_a"),
        "{e}"
    );
    // Baked: the far field's node count, with the reason and what can vary.
    let far_values = values_of(far, &HairParams::default(), None, 8);
    let e = fail(far, &far_values, &["beta_m", "nodes"]);
    let ShaderInputError::Baked {
        reason, varying, ..
    } = &e
    else {
        panic!("{e:?}")
    };
    assert!(
        reason.contains("node count") && varying.starts_with("beta_m, beta_n"),
        "{e}"
    );
    // The reference integrator has no shader form, varying or not.
    let mut reference = far_values.clone();
    reference.set("reference", InputValue::Switch(true));
    for varying in [&[][..], &["beta_m"]] {
        let e = fail(far, &reference, varying);
        assert!(
            matches!(
                e,
                ShaderInputError::NoShaderForm {
                    model: "chiang-far --reference",
                    ..
                }
            ),
            "{e:?}"
        );
        assert!(e.to_string().contains("adaptive quadrature"), "{e}");
    }
    assert!((far.shader.unwrap().varying)(&reference).is_empty());
    // Every input of Nguyen-Donnelly is in its textures.
    let nguyen = find_model("nguyen-donnelly").unwrap();
    let n_values = values_of(nguyen, &HairParams::default(), None, 8);
    let e = fail(nguyen, &n_values, &["beta_r"]);
    assert!(
        e.to_string().contains("lookup textures") && e.to_string().contains("can: none"),
        "{e}"
    );
    // Gerard's normalised lobe bakes beta_r, and switches never vary.
    let gerard = find_model("gerard").unwrap();
    let mut g_values = values_of(gerard, &HairParams::default(), None, 8);
    assert!(gerard.trace_shader(&g_values, &["beta_r"]).is_ok());
    g_values.set("hg_normalised", InputValue::Switch(true));
    let e = fail(gerard, &g_values, &["beta_r"]);
    assert!(e.to_string().contains("elliptic integral"), "{e}");
    let e = fail(gerard, &g_values, &["hg_normalised"]);
    assert!(matches!(e, ShaderInputError::Baked { .. }), "{e:?}");
    // Invalid values are the model's own error.
    let mut bad = values.clone();
    bad.set("eta", InputValue::Number(0.9));
    assert!(matches!(
        fail(chiang, &bad, &["beta_m"]),
        ShaderInputError::Param(_)
    ));
}

/// A shader with every input varying.
struct VaryingShader {
    /// The model.
    model: &'static str,
    /// Whether the query has h.
    near: bool,
    /// The graph.
    graph: Graph,
    /// The varying inputs and their scalars, in argument order.
    widths: Vec<(&'static str, usize)>,
}

/// The shaders of every traced model with every input varying at the three parameter sets
/// (the absorption as sigma_a, melanin and a colour), built once per test process.
fn all_varying() -> &'static [VaryingShader] {
    static CACHE: std::sync::OnceLock<Vec<VaryingShader>> = std::sync::OnceLock::new();
    CACHE.get_or_init(|| {
        let mut out = Vec::new();
        for (entry, shader) in traced_models() {
            for (_, hair, absorption) in hairs() {
                let values = values_of(entry, &hair, absorption, 4);
                let names = (shader.varying)(&values);
                let graph = (shader.trace)(&values, &names).unwrap();
                let near = (entry.build)(&values).unwrap().uses_offset();
                let widths = graph
                    .signature()
                    .parameters
                    .iter()
                    .filter(|p| p.constant.is_none())
                    .skip(if near { 3 } else { 2 })
                    .map(|p| p.ty.width());
                let widths = names.iter().copied().zip(widths).collect();
                out.push(VaryingShader {
                    model: entry.name,
                    near,
                    graph,
                    widths,
                });
            }
        }
        out
    })
}

/// A valid value of one scalar of input `name` from `u` in [0, 1].
fn valid(name: &str, u: f64) -> f64 {
    let (lo, hi) = match name {
        "beta_m" | "beta_n" => (0.02, 1.0),
        "alpha" => (-0.5, 0.5),
        "eta" => (1.2, 2.0),
        "sigma_a" => (0.0, 20.0),
        "color" => (0.01, 1.0),
        "eumelanin" | "pheomelanin" => (0.0, 8.0),
        "roughness" => (0.05, 1.0),
        "alpha_r" => (-0.39, 0.39),
        "beta_r" => (0.02, 0.78),
        "exponent" | "exponent_primary" | "exponent_secondary" => (0.1, 1000.0),
        "shift_primary" | "shift_secondary" => (-PI, PI),
        "tangent_shift_primary" | "tangent_shift_secondary" => (-3.0, 3.0),
        "shift_texture" | "noise_mask" => (0.0, 1.0),
        _ => (0.0, 10.0),
    };
    lo + (hi - lo) * u
}

/// A value of one scalar of input `name` outside its domain, `k` choosing which.
fn invalid(name: &str, k: usize) -> f64 {
    let options: &[f64] = match name {
        "beta_m" | "beta_n" | "roughness" | "beta_r" => &[0.0, -1.0, 5.0],
        "alpha" | "alpha_r" => &[2.0, -3.0, 100.0],
        "eta" => &[1.0, 0.0, -2.0, 10.0],
        "sigma_a" => &[-1.0, 1e30, 3e38],
        "color" => &[-0.5, 0.0, 2.0],
        "eumelanin" | "pheomelanin" => &[-1.0, 1e30],
        "exponent" | "exponent_primary" | "exponent_secondary" => &[0.0, -5.0, 1e9],
        "shift_primary" | "shift_secondary" => &[1e4, -1e4],
        "tangent_shift_primary" | "tangent_shift_secondary" => &[1e30, -1e30],
        "shift_texture" | "noise_mask" => &[-1.0, 3.0],
        _ => &[-1.0, 1e9],
    };
    options[k % options.len()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn varying_shaders_are_finite_and_non_negative(
        u in prop::collection::vec(0.0f64..=1.0, 48),
        k in prop::collection::vec(0usize..8, 48),
        bad in prop::collection::vec(0.0f64..1.0, 48),
    ) {
        for VaryingShader { model, near, graph, widths } in all_varying() {
            let mut g = Gen(u[0].to_bits() ^ u[1].to_bits());
            let mut q: Vec<f32> = [g.dir(), g.dir()].concat().iter().map(|&v| v as f32).collect();
            if *near {
                q.push((2.0 * u[2] - 1.0) as f32);
            }
            // Valid arguments: finite and non-negative.
            let mut valid_args = Vec::new();
            let mut invalid_args = Vec::new();
            let mut j = 3;
            for (name, width) in widths {
                for _ in 0..*width {
                    valid_args.push(valid(name, u[j % u.len()]) as f32);
                    let out_of_domain = bad[j % bad.len()] < 0.5;
                    invalid_args.push(match out_of_domain {
                        true => invalid(name, k[j % k.len()]) as f32,
                        false => valid(name, u[j % u.len()]) as f32,
                    });
                    j += 1;
                }
            }
            let s = graph.eval_f32(&[&q[..], &valid_args].concat());
            prop_assert!(s.iter().all(|v| v.is_finite() && *v >= 0.0), "{model}: {s:?} at {q:?} {valid_args:?}");
            let s = graph.eval_f32(&[&q[..], &invalid_args].concat());
            prop_assert!(s.iter().all(|v| !v.is_nan()), "{model}: {s:?} at {q:?} {invalid_args:?}");
            prop_assert!(s.iter().all(|v| v.is_finite()), "{model}: {s:?} at {q:?} {invalid_args:?}");
        }
    }
}
