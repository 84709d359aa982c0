//! One domain per physical parameter, checked in one place with one message: an invalid value
//! gives the same error wherever it enters (the parameter types, the named inputs the command
//! line uses, the models, the fits).

use hairmath::absorption::Absorption;
use hairmath::absorption::PathLength;
use hairmath::bcsdf::{
    AbsorptionInput, ChiangHair, FarField, FromInputs, InputValue, InputValues, Marschner2003,
};
use hairmath::fit::{lobe_energies, Directions, EnergyRule, FitSettings, TtSlice};
use hairmath::params::{AzimuthalRoughness, HairParams, RefractiveIndex};
use hairmath::registry::find_model;

/// The inputs of the Chiang models with one value replaced.
fn hair_inputs(name: &str, value: InputValue) -> InputValues {
    let mut v = InputValues::new();
    v.set("beta_m", InputValue::Number(0.3));
    v.set("beta_n", InputValue::Number(0.3));
    v.set("alpha", InputValue::Number(0.03));
    v.set("eta", InputValue::Number(1.55));
    v.set(
        "sigma_a",
        InputValue::Absorption(AbsorptionInput::SigmaA([0.5; 3])),
    );
    v.set("nodes", InputValue::Count(8));
    v.set("alpha_r", InputValue::Number(-0.08));
    v.set("beta_r", InputValue::Number(0.13));
    v.set(name, value);
    v
}

/// The messages of every error, which must all be equal.
fn assert_one_message(errors: &[String]) {
    for e in errors {
        assert_eq!(e, &errors[0], "{errors:#?}");
    }
}

#[test]
fn an_invalid_beta_n_gives_one_message_wherever_it_enters() {
    let bad = hair_inputs("beta_n", InputValue::Number(1.5));
    let registered = find_model("chiang").expect("registered");
    let errors = vec![
        AzimuthalRoughness::new(1.5).unwrap_err().to_string(),
        HairParams::from_inputs(&bad).unwrap_err().to_string(),
        ChiangHair::<f64>::from_inputs(&bad)
            .unwrap_err()
            .to_string(),
        FarField::from_inputs(&bad).unwrap_err().to_string(),
        (registered.build)(&bad)
            .err()
            .expect("an error")
            .to_string(),
        TtSlice::new(0.0, 1.5, 1.55).unwrap_err().to_string(),
    ];
    assert_eq!(
        errors[0],
        "beta_n = 1.5 is not allowed: the azimuthal roughness must be in [1e-16, 1]"
    );
    assert_one_message(&errors);
}

#[test]
fn an_invalid_eta_gives_one_message_wherever_it_enters() {
    let bad = hair_inputs("eta", InputValue::Number(5.0));
    let rule = EnergyRule::default();
    let errors = vec![
        RefractiveIndex::new(5.0).unwrap_err().to_string(),
        HairParams::from_inputs(&bad).unwrap_err().to_string(),
        Marschner2003::from_inputs(&bad).unwrap_err().to_string(),
        FitSettings::new(5.0).unwrap_err().to_string(),
        lobe_energies(5.0, 0.5, PathLength::Chord, Directions::Theta0, &rule)
            .unwrap_err()
            .to_string(),
        TtSlice::new(0.0, 0.3, 5.0).unwrap_err().to_string(),
    ];
    assert_eq!(
        errors[0],
        "eta = 5 is not allowed: the relative index of refraction must be in (1, 3]"
    );
    assert_one_message(&errors);
}

#[test]
fn an_invalid_absorption_gives_one_message_wherever_it_enters() {
    let bad = hair_inputs(
        "sigma_a",
        InputValue::Absorption(AbsorptionInput::SigmaA([0.1, -1.0, 0.0])),
    );
    let rule = EnergyRule::default();
    let errors = vec![
        Absorption::new([0.1, -1.0, 0.0]).unwrap_err().to_string(),
        Absorption::grey(-1.0).unwrap_err().to_string(),
        HairParams::from_inputs(&bad).unwrap_err().to_string(),
        Marschner2003::from_inputs(&bad).unwrap_err().to_string(),
        lobe_energies(1.55, -1.0, PathLength::Chord, Directions::Theta0, &rule)
            .unwrap_err()
            .to_string(),
    ];
    assert_eq!(
        errors[0],
        "sigma_a = -1 is not allowed: absorption must be finite and >= 0 in every channel"
    );
    assert_one_message(&errors);
}

#[test]
fn a_missing_input_is_a_typed_error() {
    let mut v = hair_inputs("beta_m", InputValue::Number(0.3));
    v.set("beta_m", InputValue::Switch(true));
    let e = ChiangHair::<f64>::from_inputs(&v).unwrap_err();
    assert_eq!(e, hairmath::ParamError::Missing { name: "beta_m" });
    assert_eq!(e.to_string(), "beta_m is required");
}

/// Issue 16, item 6: a hair colour's name means one melanin concentration everywhere
/// (`absorption::HAIR_COLOURS`): the report's lobe tables, the model comparison and its
/// README table, and `HairParams::default` (brown, eumelanin 1.3).
#[test]
fn hair_colour_names_mean_one_concentration() {
    use hairmath::absorption::HAIR_COLOURS;
    use hairmath::diagnostics::REPORT_HAIRS;
    use hairmath::fit::{ComparisonSettings, COMPARISON_COLOURS};
    let named = |name: &str| {
        *HAIR_COLOURS
            .iter()
            .find(|(n, _, _)| *n == name)
            .unwrap_or_else(|| panic!("{name} is not in HAIR_COLOURS"))
    };
    let mut names: Vec<&str> = HAIR_COLOURS.iter().map(|c| c.0).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), HAIR_COLOURS.len(), "one entry per name");
    for colour in REPORT_HAIRS.iter().chain(&COMPARISON_COLOURS) {
        assert_eq!(*colour, named(colour.0));
    }
    for hair in ComparisonSettings::full()
        .hairs
        .iter()
        .chain(&ComparisonSettings::dark_brown().hairs)
    {
        assert_eq!(
            (hair.colour, hair.eumelanin, hair.pheomelanin),
            named(hair.colour)
        );
    }
    assert_eq!(ComparisonSettings::dark_brown().hairs[0].eumelanin, 3.0);
    let (_, eu, pheo) = named("brown");
    assert_eq!(
        HairParams::default().sigma_a,
        Absorption::from_melanin(eu, pheo).unwrap()
    );
}
