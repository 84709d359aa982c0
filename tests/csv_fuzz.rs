//! Random and mutated bytes into the command line's CSV readers (`hairmath::csv`: `eval`,
//! `wigner3j`, `gaunt`) and the Wigner argument parser (`HalfInt`'s `FromStr`): no panic, the
//! output bounded by the input (each line written at most once, plus its appended values), and
//! every printed value a finite number. The `.hair` reader and the scene files of `hairmath
//! plan` have theirs in `tests/strands_hair_file.rs` and `tests/plan_scene.rs`; the fuzz
//! targets of `fuzz/` run the same properties under libFuzzer.

use hairmath::bcsdf::{Bcsdf, ChiangFarField, ChiangHair, FarFieldRule};
use hairmath::csv::{eval_filter, gaunt_filter, wigner3j_filter, CsvError};
use hairmath::params::HairParams;
use hairmath::sh::HalfInt;
use proptest::prelude::*;

/// Valid inputs the mutations start from.
const EVAL: &str =
    "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h\n0,1,0,0,0.6,0.8,0.5\n0.6,0.8,0,-0.6,0,0.8,-1\n";
const WIGNER: &str = "j1,j2,j3,m1,m2,m3\n1,1,0,0,0,0\n3/2,1/2,1,1/2,-1/2,0\n2,2,2,0,0,0\n";
const GAUNT: &str = "l1,m1,l2,m2,l3,m3\n1,0,1,0,2,0\n2,-1,1,1,3,0\n0,0,0,0,0,0\n";

/// The most bytes a row's appended values take: `,` and a number per value (24 characters at
/// most, such as `-1.2345678901234567e-300`).
const PER_VALUE: usize = 25;

/// Lines in `bytes` (LF, CR and CRLF each end one).
fn line_count(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n' || b == b'\r').count() + 1
}

/// Checks a filter's output against its input: at most the input plus `values` appended
/// values per line, UTF-8, and every row's appended values finite numbers (non-negative with
/// `non_negative`).
fn check_output(
    input: &[u8],
    out: &[u8],
    result: &Result<(), CsvError>,
    values: usize,
    non_negative: bool,
) -> Result<(), TestCaseError> {
    let bound = input.len() + line_count(input) * values * PER_VALUE;
    prop_assert!(
        out.len() <= bound,
        "{} bytes out of {}",
        out.len(),
        input.len()
    );
    let text = std::str::from_utf8(out).map_err(|e| TestCaseError::fail(e.to_string()))?;
    for line in text.lines().skip(1) {
        for value in line.rsplit(',').take(values) {
            let v: f64 = value
                .parse()
                .map_err(|_| TestCaseError::fail(format!("{value:?} in {line:?}")))?;
            prop_assert!(v.is_finite() && (!non_negative || v >= 0.0), "{line}");
        }
    }
    if let Err(CsvError::Input { line, message }) = result {
        prop_assert!(
            *line >= 1 && *line <= line_count(input),
            "line {line}: {message}"
        );
        prop_assert!(!message.is_empty());
    }
    Ok(())
}

/// `text` with each `(position, byte, kind)` edit applied: kind 0 replaces the byte at the
/// position, 1 inserts before it, 2 deletes it (positions wrap).
fn mutate(text: &str, edits: &[(usize, u8, u8)]) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    for &(at, byte, kind) in edits {
        let at = at % (bytes.len() + 1);
        match kind {
            0 if at < bytes.len() => bytes[at] = byte,
            2 if at < bytes.len() => {
                bytes.remove(at);
            }
            _ => bytes.insert(at, byte),
        }
    }
    bytes
}

/// Bytes that are mostly the characters of a CSV of numbers.
fn csv_bytes() -> impl Strategy<Value = Vec<u8>> {
    let alphabet = prop_oneof![
        Just(b','),
        Just(b'\n'),
        Just(b'\r'),
        Just(b'-'),
        Just(b'/'),
        Just(b'.'),
        Just(b'e'),
        b'0'..=b'9',
        any::<u8>(),
    ];
    proptest::collection::vec(alphabet, 0..400)
}

fn edits() -> impl Strategy<Value = Vec<(usize, u8, u8)>> {
    proptest::collection::vec((0..200_usize, any::<u8>(), 0_u8..3), 1..8)
}

fn run_eval(model: &dyn Bcsdf<f64>, input: &[u8]) -> Result<(), TestCaseError> {
    let mut out = Vec::new();
    let result = eval_filter(model, input, &mut out);
    check_output(input, &out, &result, 3, true)
}

fn run_wigner(input: &[u8]) -> Result<(), TestCaseError> {
    let mut out = Vec::new();
    let result = wigner3j_filter(input, &mut out);
    check_output(input, &out, &result, 1, false)
}

fn run_gaunt(input: &[u8], real: bool) -> Result<(), TestCaseError> {
    let mut out = Vec::new();
    let result = gaunt_filter(input, &mut out, real);
    check_output(input, &out, &result, 1, false)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn eval_reads_any_bytes(random in csv_bytes(), edits in edits()) {
        let near = ChiangHair::<f64>::new(&HairParams::default());
        let far = ChiangFarField::with_rule(&HairParams::default(), &FarFieldRule::gauss_legendre(8).unwrap());
        let mutated = mutate(EVAL, &edits);
        let mut headed = EVAL.as_bytes().to_vec();
        headed.extend(&random);
        for input in [&random, &mutated, &headed] {
            run_eval(&near, input)?;
            run_eval(&far, input)?;
        }
    }

    #[test]
    fn wigner3j_reads_any_bytes(random in csv_bytes(), edits in edits()) {
        let mut headed = WIGNER.as_bytes().to_vec();
        headed.extend(&random);
        for input in [random.clone(), mutate(WIGNER, &edits), headed] {
            run_wigner(&input)?;
        }
    }

    #[test]
    fn gaunt_reads_any_bytes(random in csv_bytes(), edits in edits(), real in any::<bool>()) {
        let mut headed = GAUNT.as_bytes().to_vec();
        headed.extend(&random);
        for input in [random.clone(), mutate(GAUNT, &edits), headed] {
            run_gaunt(&input, real)?;
        }
    }

    /// A value the Wigner argument parser accepts prints as text that parses back to it.
    #[test]
    fn half_integers_parse_any_text(
        text in proptest::string::string_regex("[-+ ]?[0-9]{0,12}([./][0-9]{0,12})?").unwrap(),
        random in ".{0,24}",
    ) {
        for text in [&text, &random] {
            if let Ok(value) = text.parse::<HalfInt>() {
                let again: HalfInt = value.to_string().parse().expect("printed values parse");
                prop_assert_eq!(again, value, "{:?}", text);
            }
        }
    }
}
