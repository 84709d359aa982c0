#![cfg(feature = "plan")]
//! The scene file of `hairmath plan`: the example of the issue parses to its values, omitted
//! keys take their defaults, and every malformed file gives a `SceneError` at the right key and
//! line whose message says what is allowed.

use hairmath::plan::{
    CostMeasure, Environment, HairKey, Lights, ParamRange, Scene, SceneError, SceneHair,
};
use proptest::prelude::*;

/// The example of the issue.
const EXAMPLE: &str = r#"budget = 0.05            # the error E against the Chiang far field, > 0
cost = "ops"             # what to minimise: "ops" (weighted traced operation counts) or "llvmpipe"
[hair]                   # each parameter: a value (baked), a [min, max] range, or { varying = [min, max] } (per pixel)
eumelanin = [0.5, 1.5]
pheomelanin = 0.0
beta_m = 0.3
beta_n = { varying = [0.3, 0.6] }
alpha_deg = 2.0
eta = 1.55
[lights]
directional = true
environment = "none"     # or "sh": an SH environment with bands l <= environment_sh_lmax
environment_sh_lmax = 2
"#;

fn parse(text: &str) -> Scene {
    match Scene::parse(text, "scene.toml") {
        Ok(scene) => scene,
        Err(e) => panic!("{e}"),
    }
}

fn error(text: &str) -> SceneError {
    match Scene::parse(text, "scene.toml") {
        Ok(scene) => panic!("parsed, expected an error: {scene:?}\n{text}"),
        Err(e) => e,
    }
}

/// `text` fails at `key` on `line`, with a message that contains `allowed`.
fn check(text: &str, key: &str, line: usize, allowed: &str) {
    let e = error(text);
    assert_eq!((e.key.as_str(), e.line), (key, line), "{e}\n{text}");
    assert_eq!(e.file, "scene.toml");
    assert!(e.message.contains(allowed), "{e} lacks {allowed:?}");
}

fn keys(hair: &SceneHair) -> Vec<HairKey> {
    hair.params().iter().map(|&(key, _)| key).collect()
}

#[test]
fn the_example_parses_to_its_values() {
    let scene = parse(EXAMPLE);
    assert_eq!(scene.budget, 0.05);
    assert_eq!(scene.cost, CostMeasure::Ops);
    let hair = &scene.hair;
    let eumelanin = ParamRange::Range { min: 0.5, max: 1.5 };
    assert_eq!(hair.get(HairKey::Eumelanin), eumelanin);
    assert_eq!(hair.get(HairKey::Pheomelanin), ParamRange::Fixed(0.0));
    assert_eq!(hair.get(HairKey::BetaM), ParamRange::Fixed(0.3));
    let beta_n = ParamRange::Varying { min: 0.3, max: 0.6 };
    assert_eq!(hair.get(HairKey::BetaN), beta_n);
    assert_eq!(hair.get(HairKey::AlphaDeg), ParamRange::Fixed(2.0));
    assert_eq!(hair.get(HairKey::Eta), ParamRange::Fixed(1.55));
    assert_eq!(keys(hair), HairKey::ALL);
    assert_eq!(hair.non_fixed(), [HairKey::Eumelanin, HairKey::BetaN]);
    let lights = Lights {
        directional: true,
        environment: Environment::None,
    };
    assert_eq!(scene.lights, lights);
}

#[test]
fn params_keep_the_file_order_and_defaults_come_last() {
    let scene = parse(
        r#"budget = 1
cost = "llvmpipe"
[hair]
beta_n = 0.3
eta = [1.5, 1.6]
eumelanin = 2
beta_m = { varying = [0.2, 0.2] }
"#,
    );
    assert_eq!(scene.budget, 1.0);
    assert_eq!(scene.cost, CostMeasure::Llvmpipe);
    let order = [
        HairKey::BetaN,
        HairKey::Eta,
        HairKey::Eumelanin,
        HairKey::BetaM,
        HairKey::Pheomelanin,
        HairKey::AlphaDeg,
    ];
    assert_eq!(keys(&scene.hair), order);
    assert_eq!(scene.hair.non_fixed(), [HairKey::Eta, HairKey::BetaM]);
    assert_eq!(scene.hair.get(HairKey::Eumelanin), ParamRange::Fixed(2.0));
    let beta_m = scene.hair.get(HairKey::BetaM);
    assert_eq!(
        (beta_m.min(), beta_m.max(), beta_m.is_fixed()),
        (0.2, 0.2, false)
    );
}

#[test]
fn omitted_keys_take_their_defaults() {
    let scene = parse(
        r#"budget = 0.1
[hair]
eumelanin = 1.3
beta_m = 0.3
beta_n = 0.3
"#,
    );
    assert_eq!(scene.cost, CostMeasure::Ops);
    assert_eq!(scene.hair.get(HairKey::Pheomelanin), ParamRange::Fixed(0.0));
    assert_eq!(scene.hair.get(HairKey::AlphaDeg), ParamRange::Fixed(2.0));
    assert_eq!(scene.hair.get(HairKey::Eta), ParamRange::Fixed(1.55));
    assert!(scene.hair.non_fixed().is_empty());
    let lights = Lights {
        directional: true,
        environment: Environment::None,
    };
    assert_eq!(scene.lights, lights);
}

#[test]
fn an_sh_environment_has_its_bands() {
    let text = |lights: &str| {
        format!("budget = 0.1\n[hair]\neumelanin = 1\nbeta_m = 0.3\nbeta_n = 0.3\n{lights}")
    };
    let default = parse(&text("[lights]\nenvironment = \"sh\"\n")).lights;
    assert_eq!(default.environment, Environment::Sh { lmax: 2 });
    let only_sh = "[lights]\ndirectional = false\nenvironment = \"sh\"\nenvironment_sh_lmax = 8\n";
    let lights = Lights {
        directional: false,
        environment: Environment::Sh { lmax: 8 },
    };
    assert_eq!(parse(&text(only_sh)).lights, lights);
}

#[test]
fn unknown_keys_are_errors() {
    let top = r#"budget = 0.05
colour = 3
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
"#;
    check(
        top,
        "colour",
        2,
        "the keys of a scene file are budget, cost, hair, lights",
    );
    let hair = r#"budget = 0.05
[hair]
eumelanin = 1.0
colour = "brown"
beta_m = 0.3
beta_n = 0.3
"#;
    let keys = "the keys of [hair] are eumelanin, pheomelanin, beta_m, beta_n, alpha_deg, eta";
    check(hair, "hair.colour", 4, keys);
    let lights = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
[lights]
directional = true
ambient = true
"#;
    let keys = "the keys of [lights] are directional, environment, environment_sh_lmax";
    check(lights, "lights.ambient", 8, keys);
    let varying = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = { per_pixel = [0.3, 0.6] }
"#;
    check(varying, "hair.beta_n.per_pixel", 5, "varying");
}

#[test]
fn wrong_types_are_errors_at_the_key() {
    let budget = r#"cost = "ops"
budget = "0.05"
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
"#;
    let e = error(budget);
    assert_eq!(
        e.to_string(),
        "scene.toml:2: budget: expected a number, found a string"
    );
    let directional = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
[lights]
directional = 1
"#;
    check(
        directional,
        "lights.directional",
        7,
        "expected a boolean, true or false",
    );
    let environment = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
[lights]
environment = false
"#;
    check(
        environment,
        "lights.environment",
        7,
        "expected \"none\" or \"sh\"",
    );
    let hair_value = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = "0.3"
beta_n = 0.3
"#;
    let allowed =
        "expected a number, a [min, max] range or { varying = [min, max] }, found a string";
    check(hair_value, "hair.beta_m", 4, allowed);
    let hair_table = r#"budget = 0.05
hair = 3
"#;
    check(
        hair_table,
        "hair",
        2,
        "expected a table [hair], found an integer",
    );
    let cost = r#"budget = 0.05
cost = 1
[hair]
"#;
    check(cost, "cost", 2, "\"ops\"");
}

#[test]
fn malformed_ranges_are_errors() {
    let three = r#"budget = 0.05
[hair]
eumelanin = [0.5, 1.0, 1.5]
beta_m = 0.3
beta_n = 0.3
"#;
    check(
        three,
        "hair.eumelanin",
        3,
        "expected [min, max], two numbers, found 3 values",
    );
    let not_numbers = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = { varying = [
  0.3,
  "0.6",
] }
"#;
    let allowed = "expected [min, max], two numbers, found a string";
    check(not_numbers, "hair.beta_n.varying", 7, allowed);
    let reversed = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = { varying = [0.6, 0.3] }
"#;
    let e = error(reversed);
    assert_eq!(
        e.to_string(),
        "scene.toml:5: hair.beta_n: min 0.6 > max 0.3: a range is [min, max] with min <= max"
    );
}

#[test]
fn values_outside_their_domains_are_errors_at_the_value() {
    let roughness = "the longitudinal roughness must be in [1e-16, 1]";
    let zero = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_n = 0.3
beta_m = 0
"#;
    check(
        zero,
        "hair.beta_m",
        5,
        &format!("beta_m = 0 is not allowed: {roughness}"),
    );
    let big = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 1.5
beta_n = 0.3
"#;
    check(
        big,
        "hair.beta_m",
        4,
        &format!("beta_m = 1.5 is not allowed: {roughness}"),
    );
    let range = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = [0.0, 0.5]
beta_n = 0.3
"#;
    check(range, "hair.beta_m", 4, roughness);
    let eta = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
eta = 1.0
"#;
    let index = "eta = 1 is not allowed: the relative index of refraction must be in (1, 3]";
    check(eta, "hair.eta", 6, index);
    let alpha = r#"budget = 0.05
[hair]
alpha_deg = 95
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
"#;
    check(alpha, "hair.alpha_deg", 3, "finite with |alpha_deg| < 90");
    let eumelanin = r#"budget = 0.05
[hair]
beta_m = 0.3
beta_n = 0.3
eumelanin = -1
"#;
    let melanin = "eumelanin = -1 is not allowed: melanin concentrations must be in [0, 1e300] (sigma_a must be finite)";
    check(eumelanin, "hair.eumelanin", 5, melanin);
    let pheomelanin = r#"budget = 0.05
[hair]
eumelanin = 1.0
pheomelanin = { varying = [-1, 1] }
beta_m = 0.3
beta_n = 0.3
"#;
    check(pheomelanin, "hair.pheomelanin", 4, "must be in [0, 1e300]");
}

#[test]
fn the_budget_is_positive_and_finite() {
    let budget = |value: &str| {
        format!("cost = \"ops\"\n\nbudget = {value}\n[hair]\neumelanin = 1\nbeta_m = 0.3\nbeta_n = 0.3\n")
    };
    let e = error(&budget("0"));
    assert_eq!(
        e.to_string(),
        "scene.toml:3: budget: 0 is not allowed: the budget is a finite error E > 0"
    );
    check(&budget("-1"), "budget", 3, "E > 0");
    check(&budget("inf"), "budget", 3, "finite");
    check(&budget("nan"), "budget", 3, "finite");
}

#[test]
fn missing_keys_are_errors_at_their_table() {
    let no_hair = r#"
budget = 0.05
[lights]
directional = true
"#;
    check(no_hair, "hair", 1, "a [hair] table");
    let no_budget = r#"[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
"#;
    check(no_budget, "budget", 1, "budget = E");
    let no_beta_m = r#"budget = 0.05

[hair]
eumelanin = 1.0
beta_n = 0.3
"#;
    check(
        no_beta_m,
        "hair.beta_m",
        3,
        "[hair] must give eumelanin, beta_m and beta_n",
    );
    let no_varying = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = {}
"#;
    check(
        no_varying,
        "hair.beta_n.varying",
        5,
        "{ varying = [min, max] }",
    );
}

#[test]
fn lights_are_checked() {
    let sky = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
[lights]
environment = "sky"
"#;
    check(
        sky,
        "lights.environment",
        7,
        "the environment is \"none\" or \"sh\"",
    );
    let lmax = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
[lights]
environment = "sh"
environment_sh_lmax = 9
"#;
    check(lmax, "lights.environment_sh_lmax", 8, "an integer in 0..=8");
    check(
        &lmax.replace("= 9", "= 2.0"),
        "lights.environment_sh_lmax",
        8,
        "expected an integer in 0..=8, found a float",
    );
    let dark = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3

[lights]
directional = false
"#;
    check(
        dark,
        "lights",
        7,
        "a scene needs directional = true, environment = \"sh\", or both",
    );
}

#[test]
fn syntax_errors_have_their_line() {
    let text = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = = 0.3
beta_n = 0.3
"#;
    check(text, "", 4, "not valid TOML");
    let duplicate = r#"budget = 0.05
[hair]
eumelanin = 1.0
beta_m = 0.3
beta_n = 0.3
beta_m = 0.4
"#;
    check(duplicate, "", 6, "duplicate key");
}

#[test]
fn files_are_read_and_unreadable_ones_are_errors() {
    let path =
        std::env::temp_dir().join(format!("hairmath-plan-scene-{}.toml", std::process::id()));
    let written = std::fs::write(&path, EXAMPLE);
    assert!(written.is_ok(), "{written:?}");
    let scene = Scene::read(&path);
    let _ = std::fs::remove_file(&path);
    assert_eq!(scene, Ok(parse(EXAMPLE)));
    let missing = path.with_extension("missing.toml");
    let e = match Scene::read(&missing) {
        Ok(scene) => panic!("read a missing file: {scene:?}"),
        Err(e) => e,
    };
    assert_eq!((e.line, e.key.as_str()), (0, ""));
    assert_eq!(e.file, missing.display().to_string());
    assert!(e.message.starts_with("cannot read the scene file"), "{e}");
}

/// Checks that parsing `text` does not panic and that an error has a line in the text.
fn parses_or_locates(text: &str) -> Result<(), TestCaseError> {
    if let Err(e) = Scene::parse(text, "scene.toml") {
        let lines = 1 + text.matches('\n').count();
        prop_assert!(e.line >= 1 && e.line <= lines, "{e} outside 1..={lines}");
        prop_assert!(!e.message.is_empty());
    }
    Ok(())
}

/// Applies `(position, byte, operation)` edits to `text`: insert, replace or delete a byte.
fn mutate(text: &str, edits: &[(usize, u8, u8)]) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for &(at, byte, op) in edits {
        let at = at % (bytes.len() + 1);
        match op % 3 {
            0 => bytes.insert(at, byte),
            1 if at < bytes.len() => bytes[at] = byte,
            _ if at < bytes.len() => {
                bytes.remove(at);
            }
            _ => {}
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..256)) {
        parses_or_locates(&String::from_utf8_lossy(&bytes))?;
    }

    #[test]
    fn mutated_examples_never_panic(
        edits in proptest::collection::vec((0..EXAMPLE.len() + 1, any::<u8>(), 0u8..3), 1..6),
        printable in proptest::collection::vec((0..EXAMPLE.len() + 1, 32u8..127, 0u8..3), 1..6),
    ) {
        parses_or_locates(&mutate(EXAMPLE, &edits))?;
        parses_or_locates(&mutate(EXAMPLE, &printable))?;
    }
}
