//! Trace tests of shader code with varying inputs (`hairmath::bcsdf::{VaryingInputs,
//! ShaderInputs, InputsIn, AbsorptionIn}`) and of the generic derivations of the uniforms: for
//! every traceable model, its uniforms derived from symbolic arguments and its shader
//! ([`ShaderInputs::trace`], every input of `VARYING` at once) against the `f32` derivation bit
//! for bit, on arguments inside and outside the inputs' domains (where the shader clamps: no
//! NaN), with the hard direction pairs.

use super::*;
use hairmath::absorption::{log_color_of_sigma_a, sigma_a_of_color, sigma_a_of_melanin};
use hairmath::bcsdf::{
    varying_names, AbsorptionIn, AbsorptionInput, FarField, FromInputs, InputValue, InputValues,
    InputsIn, ShaderInputs, ValueIn, VaryingInputs,
};
use hairmath::models::{
    Approximation, Frostbite, FrostbiteRefit, Gerard, KajiyaKay, Karis, KarisRefit, NguyenDonnelly,
    Scheuermann, TressFx,
};
use hairmath::params::marschner_lobes;

/// The domain of one scalar of a varying argument, by input name: the valid range, with
/// special values at and beyond its ends (the shader clamps those).
fn domain(name: &str) -> Arg {
    match name {
        "beta_m" | "beta_n" => arg(0.01, 1.0, &[0.01, 1.0, 0.0, -1.0, 2.0]),
        "alpha" => arg(-1.5, 1.5, &[0.0, 1.5, 1.6, -2.0]),
        "eta" => arg(1.0001, 3.0, &[1.0001, 1.55, 1.0, 0.5, 3.5]),
        "sigma_a" => arg(0.0, 10.0, &[0.0, 10.0, -1.0, 1e30]),
        "color" => arg(0.01, 1.0, &[1.0, 1e-3, 0.0, -0.5, 1.5]),
        "eumelanin" | "pheomelanin" => arg(0.0, 8.0, &[0.0, 8.0, -1.0, 100.0]),
        "roughness" => arg(1.0 / 255.0, 1.0, &[1e-3, 1.0, 0.0, -0.5, 2.0]),
        "alpha_r" => arg(-0.39, 0.39, &[0.0, 0.39, 1.0, -1.0]),
        "beta_r" => arg(0.02, 0.78, &[0.02, 0.78, 0.0, -0.1, 1.0]),
        "exponent" | "exponent_primary" | "exponent_secondary" => {
            arg(0.1, 1e4, &[1e-3, 1e6, 0.0, -1.0, 2e6])
        }
        "shift_primary" | "shift_secondary" => arg(-PI, PI, &[0.0, PI, 10.0, -100.0]),
        "tangent_shift_primary" | "tangent_shift_secondary" => arg(-3.0, 3.0, &[0.0, 1e6, -1e6]),
        "shift_texture" | "noise_mask" => arg(0.0, 1.0, &[0.0, 1.0, -1.0, 2.0]),
        // Weights per channel.
        _ => arg(0.0, 10.0, &[0.0, 1e6, -1.0, 2e6]),
    }
}

/// The arguments of `inputs`: its given values first (the hard rows), then random ones of
/// [`domain`].
fn arguments<M: VaryingInputs>(inputs: &ShaderInputs<'_, M>, g: &mut Gen) -> Vec<f64> {
    let mut out = Vec::new();
    for (name, p) in inputs.names().iter().zip(inputs.parameters()) {
        for _ in 0..p.ty.width() {
            out.push(g.pick(&domain(name)));
        }
    }
    out
}

/// Checks the uniforms and the shader of `model` (built from `values`) with every input that
/// can vary for these values as an argument: the traced graphs interpreted in `f32` against
/// the `f32` code bit for bit (naga validates the WGSL).
fn check_varying<M: VaryingInputs>(label: &str, model: &M, values: &InputValues) {
    let names = varying_names::<M>(values);
    let inputs = ShaderInputs::new(model, values, &names).unwrap();
    let n = inputs.argument_count();
    let given = inputs.given_arguments();
    // The uniforms: as the shader computes them, and every one derived.
    let graph = trace(n, |x| {
        [
            inputs.uniforms(x).to_values(),
            M::uniforms_in(&inputs.inputs(x)).to_values(),
        ]
        .concat()
    });
    let mut first = vec![given.clone()];
    first.extend((0..4).map(|k| {
        let mut g = Gen(k);
        arguments(&inputs, &mut g)
    }));
    let rows = listed_then(first, |g| arguments(&inputs, g));
    check(&format!("{label}: uniforms"), &rows, &graph, |x| {
        [
            inputs.uniforms(x).to_values(),
            M::uniforms_in(&inputs.inputs(x)).to_values(),
        ]
        .concat()
    });
    // The shader: the query, then the arguments.
    let shader = inputs.trace();
    let query = |g: &mut Gen| match model.uses_offset() {
        true => g.query(),
        false => g.pair(),
    };
    let mut first = Vec::new();
    for p in HARD_PAIRS {
        let h: &[f64] = if model.uses_offset() { &[0.5] } else { &[] };
        first.push([&p[..], h, &given].concat());
    }
    let rows = listed_then(first, |g| [query(g), arguments(&inputs, g)].concat());
    let q = if model.uses_offset() { 7 } else { 6 };
    check(&format!("{label}: shader"), &rows, &shader, |x| {
        let m = model.with_uniforms(inputs.uniforms(&x[q..]));
        m.eval(&query_of(&x[..q])).to_vec()
    });
}

/// The values of brown hair ([`HairParams::default`]) for the inputs of `chiang`, the
/// absorption given as `absorption`.
fn hair_values(absorption: AbsorptionInput) -> InputValues {
    let h = HairParams::default();
    let mut v = InputValues::new();
    v.set("beta_m", InputValue::Number(h.beta_m.get()));
    v.set("beta_n", InputValue::Number(h.beta_n.get()));
    v.set("alpha", InputValue::Number(h.alpha.get()));
    v.set("eta", InputValue::Number(h.eta.get()));
    v.set("sigma_a", InputValue::Absorption(absorption));
    v
}

/// The absorption of brown hair in each of its forms.
fn absorptions() -> [AbsorptionInput; 3] {
    [
        AbsorptionInput::Melanin {
            eumelanin: 1.3,
            pheomelanin: 0.2,
        },
        AbsorptionInput::SigmaA([0.545, 0.906, 1.781]),
        AbsorptionInput::Color([0.3, 0.2, 0.1]),
    ]
}

/// `values` with the absorption replaced by `absorption`.
fn with_absorption(values: &InputValues, absorption: AbsorptionInput) -> InputValues {
    let mut v = values.clone();
    v.set("sigma_a", InputValue::Absorption(absorption));
    v
}

/// Checks the approximation `M` at its mapped inputs for brown hair, with the absorption in
/// each form where it has one.
fn check_approximation<M: VaryingInputs + Approximation>(label: &str) {
    let mapped = M::mapped_inputs(&HairParams::default());
    let mut sets = vec![mapped.clone()];
    if mapped.get("sigma_a").is_some() {
        sets = absorptions()
            .iter()
            .map(|&a| with_absorption(&mapped, a))
            .collect();
    }
    for values in sets {
        let model = M::from_inputs(&values).unwrap();
        check_varying(label, &model, &values);
    }
}

traced_tests! {
    varying_closed_forms [
        "sigma_a_of_color", "log_color_of_sigma_a", "sigma_a_of_melanin", "marschner_lobes"
    ] {
        // Colours inside (0, 1] and out of it (clamped), beta_n over [0, 1].
        let colour = arg(1e-3, 1.0, &[1.0, 1e-3, 0.0, -0.5, 1.5]);
        case!("sigma_a_of_color", scalars(&[colour, UNIT]), |x| {
            vec![sigma_a_of_color(x[0], x[1])]
        });
        case!("log_color_of_sigma_a", scalars(&[SIGMA_A, UNIT]), |x| {
            vec![log_color_of_sigma_a(x[0], x[1])]
        });
        let melanin = arg(0.0, 8.0, &[0.0, 8.0, -1.0]);
        case!("sigma_a_of_melanin", scalars(&[melanin, melanin]), |x| {
            sigma_a_of_melanin(x[0], x[1]).to_vec()
        });
        case!("marschner_lobes", scalars(&[HALF_ANGLE, UNIT]), |x| {
            marschner_lobes(x[0], x[1]).iter().flat_map(|&(a, b)| [a, b]).collect()
        });
    }
    varying_inputs_in [
        "InputsIn::constant", "InputsIn::given", "InputsIn::vary", "InputsIn::get",
        "InputsIn::number", "InputsIn::rgb", "InputsIn::absorption", "InputsIn::switch",
        "AbsorptionIn::of", "AbsorptionIn::sigma_a"
    ] {
        // Given values as constants, varied ones from the arguments, every absorption form.
        let mut values = hair_values(absorptions()[0]);
        values.set("kd", InputValue::Rgb([0.1, 0.2, 0.3]));
        values.set("reference", InputValue::Switch(true));
        let colour = arg(1e-3, 1.0, &[1.0, 0.0, -0.5, 1.5]);
        let inputs = scalars(&[UNIT, colour, colour, colour, SIGMA_A, UNIT]);
        case!("InputsIn", inputs, |x| {
            let mut i = InputsIn::constant(&values);
            assert!(i.switch("reference") && !i.switch("nodes") && i.given() == &values);
            let before = [i.number("beta_m"), i.rgb("kd")[2]];
            i.vary("beta_m", ValueIn::Number(x[0]));
            i.vary("kd", ValueIn::Rgb([x[1], x[2], x[3]]));
            let melanin = i.absorption("sigma_a").sigma_a(x[5]);
            i.vary("sigma_a", ValueIn::Absorption(AbsorptionIn::Color([x[1], x[2], x[3]])));
            let colour = i.absorption("sigma_a").sigma_a(x[5]);
            let sigma = AbsorptionIn::SigmaA([x[4], -x[4], x[0]]).sigma_a(x[5]);
            let constant = AbsorptionIn::of(AbsorptionInput::Color([0.5; 3])).sigma_a(x[5]);
            assert!(i.get("nodes").is_none());
            [
                before.to_vec(),
                vec![i.number("beta_m"), i.number("eta")],
                i.rgb("kd").to_vec(),
                melanin.to_vec(),
                colour.to_vec(),
                sigma.to_vec(),
                constant.to_vec(),
            ]
            .concat()
        });
    }
    varying_reference_models [
        "ChiangHair::uniforms_in", "ChiangFarField::uniforms_in", "ShaderInputs::inputs",
        "ShaderInputs::uniforms"
    ] {
        for absorption in absorptions() {
            let values = hair_values(absorption);
            let near = ChiangHair::from_inputs(&values).unwrap();
            check_varying("chiang", &near, &values);
            // A small rule keeps the far field's shader short; the loop is the same for more.
            let mut values = values.clone();
            values.set("nodes", InputValue::Count(4));
            let FarField::Rule(far) = FarField::from_inputs(&values).unwrap() else {
                panic!("the fixed rule")
            };
            check_varying("chiang-far", &far, &values);
        }
    }
    varying_classic ["KajiyaKay::uniforms_in", "TressFx::uniforms_in", "Scheuermann::uniforms_in"] {
        check_approximation::<KajiyaKay<f64>>("kajiya-kay");
        check_approximation::<TressFx<f64>>("tressfx");
        check_approximation::<Scheuermann<f64>>("scheuermann");
    }
    varying_unreal_frostbite [
        "Karis::uniforms_in", "KarisRefit::uniforms_in", "Frostbite::uniforms_in",
        "FrostbiteRefit::uniforms_in"
    ] {
        check_approximation::<Karis<f64>>("karis");
        check_approximation::<KarisRefit<f64>>("karis-refit");
        check_approximation::<Frostbite<f64>>("frostbite");
        check_approximation::<FrostbiteRefit<f64>>("frostbite-refit");
    }
    varying_composed ["ComposedHair::uniforms_in"] {
        for absorption in absorptions() {
            let values = hair_values(absorption);
            let hair = HairParams::from_inputs(&values).unwrap();
            for composition in super::composed::compositions() {
                let model = hairmath::models::ComposedHair::new(&hair, composition).unwrap();
                check_varying("composed", &model, &values);
            }
        }
    }
    varying_tables ["NguyenDonnelly::uniforms_in", "Gerard::uniforms_in"] {
        // Nguyen-Donnelly varies nothing: its shader is the baked one.
        check_approximation::<NguyenDonnelly<f64>>("nguyen-donnelly");
        check_approximation::<Gerard<f64>>("gerard");
        // The normalised lobe bakes beta_r (and the refit exponents change constants only).
        let mut values = Gerard::mapped_inputs(&HairParams::default());
        values.set("hg_normalised", InputValue::Switch(true));
        values.set("refit_absorption", InputValue::Switch(true));
        assert!(!varying_names::<Gerard<f64>>(&values).contains(&"beta_r"));
        check_varying("gerard --hg-normalised", &Gerard::from_inputs(&values).unwrap(), &values);
    }
}
