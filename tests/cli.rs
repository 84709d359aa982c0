//! Integration tests of the `hairmath` command-line tool.

use hairmath::absorption::Absorption;
use hairmath::bcsdf::{Bcsdf, ChiangFarField, ChiangHair, FarFieldRule, Query, ReferenceFarField};
use hairmath::geometry::V3;
use hairmath::params::{HairParams, HairValues, RefractiveIndex};
use hairmath::sh::{gaunt_complex, gaunt_real};
use std::process::Output;

mod piped;
use piped::hairmath_piped;

const HEADER: &str = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h";

/// The standard flags of these tests: Chiang with sigma_a given directly.
const FLAGS: [&str; 8] = [
    "--beta-m",
    "0.3",
    "--beta-n",
    "0.25",
    "--alpha-deg",
    "3",
    "--sigma-a",
    "0.5,0.8,1.4",
];

/// `hairmath eval` with the standard flags plus `extra`.
fn eval(extra: &[&str], stdin: &str) -> Output {
    let mut args = vec!["eval"];
    args.extend(FLAGS);
    args.extend(extra);
    hairmath_piped(&args, stdin)
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The parameters of the standard flags.
fn standard_params() -> HairParams {
    HairParams::try_from(HairValues {
        beta_m: 0.3,
        beta_n: 0.25,
        alpha: 3f64.to_radians(),
        eta: 1.55,
        sigma_a: [0.5, 0.8, 1.4],
    })
    .unwrap()
}

/// The model of the standard flags.
fn standard_hair() -> ChiangHair<f64> {
    ChiangHair::new(&standard_params())
}

/// The far field of the standard flags with `n` nodes.
fn standard_far(n: usize) -> ChiangFarField<f64> {
    ChiangFarField::with_rule(
        &standard_params(),
        &FarFieldRule::gauss_legendre(n).unwrap(),
    )
}

/// `w` normalised, as the tool does.
fn unit(w: [f64; 3]) -> V3<f64> {
    let v = V3::new(w[0], w[1], w[2]);
    v.scale(1.0 / v.dot(v).sqrt())
}

/// The library's value for the standard flags, with directions normalised as the tool does.
fn expected(wi: [f64; 3], wo: [f64; 3], h: f64) -> [f64; 3] {
    standard_hair().eval(&Query::new(unit(wi), unit(wo), h))
}

/// The last three fields of a CSV line as numbers.
fn appended(line: &str) -> [f64; 3] {
    let fields: Vec<f64> = line
        .rsplit(',')
        .take(3)
        .map(|f| f.parse().expect("a number"))
        .collect();
    [fields[2], fields[1], fields[0]]
}

/// Asserts a failure with status 2 whose stderr contains every one of `needles`.
fn assert_fails_with(o: &Output, needles: &[&str]) {
    assert_eq!(o.status.code(), Some(2), "stderr: {}", stderr(o));
    let err = stderr(o);
    for needle in needles {
        assert!(err.contains(needle), "{needle:?} not in stderr: {err}");
    }
}

#[test]
fn eval_matches_the_library() {
    let third = 1.0 / 3.0;
    let rows = [
        ([0.36, 0.48, 0.8], [-0.28, 0.96, 0.0], 0.4),
        ([0.0, 1.0, 0.0], [0.0, -1.0, 0.0], -0.95),
        ([2.0 * third, third, -2.0 * third], [0.6, 0.0, -0.8], 0.0),
    ];
    let mut input = format!("{HEADER}\n");
    for (wi, wo, h) in rows {
        input += &format!(
            "{},{},{},{},{},{},{h}\n",
            wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]
        );
    }
    let o = eval(&[], &input);
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 4, "{out}");
    assert_eq!(lines[0], format!("{HEADER},f_r,f_g,f_b"));
    for (line, (wi, wo, h)) in lines[1..].iter().zip(rows) {
        let want = expected(wi, wo, h);
        assert_eq!(appended(line), want, "{line}");
        assert!(want.iter().all(|&v| v > 0.0));
    }
}

#[test]
fn eval_passes_other_columns_through_in_place() {
    let input = "id , h,wo_x,wo_y,wo_z,label,wi_x,wi_y,wi_z\n\
                 17,0.25,0,0.6,0.8,strand A,0.6,0.8,0\n";
    let o = eval(&["--model", "chiang"], input);
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "id , h,wo_x,wo_y,wo_z,label,wi_x,wi_y,wi_z,f_r,f_g,f_b"
    );
    assert!(lines[1].starts_with("17,0.25,0,0.6,0.8,strand A,0.6,0.8,0,"));
    let want = expected([0.6, 0.8, 0.0], [0.0, 0.6, 0.8], 0.25);
    assert_eq!(appended(lines[1]), want);
}

#[test]
fn melanin_and_color_are_alternatives() {
    let input = format!("{HEADER}\n0,1,0,0,0.6,0.8,0.1\n");
    let base = ["eval", "--beta-m", "0.3", "--beta-n", "0.3"];
    for flag in [["--melanin", "1.3,0.2"], ["--color", "0.5,0.3,0.1"]] {
        let args: Vec<&str> = base.iter().chain(&flag).copied().collect();
        let o = hairmath_piped(&args, &input);
        assert!(o.status.success(), "{flag:?}: {}", stderr(&o));
        assert_eq!(stdout(&o).lines().count(), 2);
    }
}

#[test]
fn missing_flag_is_a_clap_error() {
    let o = hairmath_piped(&["eval", "--beta-n", "0.3", "--sigma-a", "0,0,0"], "");
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--beta-m"), "{}", stderr(&o));
    let o = hairmath_piped(&["eval", "--beta-m", "0.3", "--beta-n", "0.3"], "");
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--sigma-a"), "{}", stderr(&o));
}

#[test]
fn two_absorption_flags_are_rejected() {
    let o = eval(&["--melanin", "1,0"], &format!("{HEADER}\n"));
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("--melanin") && err.contains("--sigma-a"),
        "{err}"
    );
    assert!(stdout(&o).is_empty());
}

#[test]
fn malformed_row_reports_its_line_after_earlier_output() {
    let input = format!("{HEADER}\n0,1,0,0,1,0,0.5\n0,1,zero,0,1,0,0.5\n0,1,0,0,1,0,0.5\n");
    let o = eval(&[], &input);
    assert_fails_with(&o, &["line 3", "wi_z", "\"zero\""]);
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 2, "{out}");
    assert_eq!(
        appended(lines[1]),
        expected([0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 0.5)
    );

    let o = eval(&[], &format!("{HEADER}\n0,1,0,0,1,0\n"));
    assert_fails_with(&o, &["line 2", "expected 7 fields", "found 6"]);
    let o = eval(&[], &format!("{HEADER}\n0,1,0,0,1,0,NaN\n"));
    assert_fails_with(&o, &["line 2", "column h", "not a finite number"]);
}

#[test]
fn non_unit_vector_and_bad_h_are_rejected() {
    let o = eval(&[], &format!("{HEADER}\n0,1,0,0,1,0,0\n0,1,0,0,1.1,0,0\n"));
    assert_fails_with(&o, &["line 3", "wo = (0, 1.1, 0)", "length 1.1"]);
    assert_eq!(stdout(&o).lines().count(), 2);
    // Within the tolerance the direction is accepted (and normalised).
    let o = eval(&[], &format!("{HEADER}\n0,1.0005,0,0,1,0,0\n"));
    assert!(o.status.success(), "{}", stderr(&o));
    let o = eval(&[], &format!("{HEADER}\n0,1,0,0,1,0,1.5\n"));
    assert_fails_with(&o, &["line 2", "h = 1.5", "[-1, 1]"]);
}

#[test]
fn missing_column_is_reported_on_line_1() {
    let o = eval(&[], "wi_x,wi_y,wi_z,wo_x,wo_y,h\n0,1,0,0,1,0\n");
    assert_fails_with(&o, &["line 1", "wo_z"]);
    assert!(stdout(&o).is_empty());
}

#[test]
fn bad_parameters_are_rejected() {
    let o = hairmath_piped(
        &[
            "eval",
            "--beta-m",
            "0",
            "--beta-n",
            "0.3",
            "--sigma-a",
            "1,1,1",
        ],
        &format!("{HEADER}\n"),
    );
    assert_fails_with(&o, &["beta_m = 0", "[1e-16, 1]"]);
    let o = eval(&["--eta", "0.9"], &format!("{HEADER}\n"));
    assert_fails_with(&o, &["eta = 0.9"]);
    let o = hairmath_piped(
        &[
            "eval",
            "--beta-m",
            "0.3",
            "--beta-n",
            "0.3",
            "--sigma-a",
            "-1,0,0",
        ],
        &format!("{HEADER}\n"),
    );
    assert_fails_with(&o, &["sigma_a = -1"]);
}

#[test]
fn report_quick_prints_the_tables() {
    let o = hairmath_piped(&["report", "--quick"], "");
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let out = stdout(&o);
    for needle in [
        "| hair | eu | pheo | sigma_a (R, G, B) | R | TT | TRT | residual | total (R, G, B) |",
        "| blonde |",
        "| black |",
        "White furnace",
        "beta 0.9:",
        "ns per call (f64)",
        "ns per call (f32)",
        "indicative; see `cargo bench` for criterion figures",
        "## Far field",
        "| hair | R | TT | TRT | residual | total (R, G, B) | vs near |",
        "### Far-field white furnace",
        "### Far-field integrator",
        "| beta_n | ref us | ref refinement | N = 8 | N = 16 | N = 32 | N = 64 | N = 128 |",
        "| 0.05 | ",
        "| ns per fast N_p |",
    ] {
        assert!(out.contains(needle), "{needle:?} not in:\n{out}");
    }
}

/// Direction pairs of the far-field tests.
const FAR_ROWS: [([f64; 3], [f64; 3]); 3] = [
    ([0.36, 0.48, 0.8], [-0.28, 0.96, 0.0]),
    ([0.0, 1.0, 0.0], [0.0, -1.0, 0.0]),
    ([0.6, 0.0, -0.8], [0.0, 0.6, 0.8]),
];

/// `FAR_ROWS` as CSV without an h column.
fn far_input() -> String {
    let mut input = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n".to_string();
    for (wi, wo) in FAR_ROWS {
        input += &format!(
            "{},{},{},{},{},{}\n",
            wi[0], wi[1], wi[2], wo[0], wo[1], wo[2]
        );
    }
    input
}

#[test]
fn chiang_far_matches_the_library_without_h() {
    for (extra, model) in [
        (&[][..], standard_far(64)),
        (&["--nodes", "8"][..], standard_far(8)),
    ] {
        let args: Vec<&str> = ["--model", "chiang-far"]
            .iter()
            .chain(extra)
            .copied()
            .collect();
        let o = eval(&args, &far_input());
        assert!(o.status.success(), "stderr: {}", stderr(&o));
        let out = stdout(&o);
        let lines: Vec<&str> = out.lines().collect();
        assert_eq!(lines[0], "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,f_r,f_g,f_b");
        assert_eq!(lines.len(), 1 + FAR_ROWS.len(), "{out}");
        for (line, (wi, wo)) in lines[1..].iter().zip(FAR_ROWS) {
            let want = model.eval(&Query::far(unit(wi), unit(wo)));
            assert_eq!(appended(line), want, "{extra:?}: {line}");
            assert!(want.iter().all(|&v| v > 0.0));
        }
    }
}

#[test]
fn chiang_far_reference_matches_the_library() {
    let o = eval(&["--model", "chiang-far", "--reference"], &far_input());
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let out = stdout(&o);
    let fast = standard_far(64);
    for (line, (wi, wo)) in out.lines().skip(1).zip(FAR_ROWS) {
        let want = ReferenceFarField::new(&standard_params(), 1e-9)
            .unwrap()
            .eval_with_error(&Query::far(unit(wi), unit(wo)))
            .value;
        assert_eq!(appended(line), want, "{line}");
        let fast = fast.eval(&Query::far(unit(wi), unit(wo)));
        assert!(
            (fast[1] - want[1]).abs() <= 1e-3 * want[1],
            "{fast:?} {want:?}"
        );
    }
}

#[test]
fn h_is_optional_only_for_chiang_far() {
    let with_h = format!("{HEADER}\n0,1,0,0,0.6,0.8,2\n");
    let o = eval(&["--model", "chiang-far"], &with_h);
    assert!(
        o.status.success(),
        "h is ignored, even out of range: {}",
        stderr(&o)
    );
    let want = standard_far(64).eval(&Query::far(unit([0.0, 1.0, 0.0]), unit([0.0, 0.6, 0.8])));
    assert_eq!(appended(stdout(&o).lines().nth(1).unwrap_or("")), want);

    let o = eval(&["--model", "chiang"], &far_input());
    assert_fails_with(&o, &["line 1", "missing column(s) h"]);
    assert!(stdout(&o).is_empty());
}

#[test]
fn far_field_flags_are_checked() {
    let o = eval(&["--model", "chiang", "--nodes", "8"], &far_input());
    assert_fails_with(
        &o,
        &["--nodes and --reference apply only to --model chiang-far"],
    );
    let o = eval(&["--model", "chiang-far", "--nodes", "0"], &far_input());
    assert_fails_with(&o, &["nodes = 0"]);
    let o = eval(
        &["--model", "chiang-far", "--nodes", "8", "--reference"],
        "",
    );
    assert!(!o.status.success());
    assert!(stderr(&o).contains("cannot be used with"), "{}", stderr(&o));
}

/// The appended `value` of each output row.
fn values(out: &str) -> Vec<f64> {
    out.lines()
        .skip(1)
        .map(|l| {
            l.rsplit(',')
                .next()
                .unwrap_or("")
                .parse()
                .expect("a number")
        })
        .collect()
}

#[test]
fn wigner3j_known_values_and_selection_rules() {
    let input = "j1,j2,j3,m1,m2,m3\n1,1,0,0,0,0\n1/2,1/2,1,0.5,-1/2,0\n1,1,5,0,0,0\n\
                 2,2,2,1,1,1\n";
    let o = hairmath_piped(&["wigner3j"], input);
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let out = stdout(&o);
    assert_eq!(out.lines().next(), Some("j1,j2,j3,m1,m2,m3,value"));
    assert!(out.contains("\n1,1,0,0,0,0,-0.5773502691896257\n"), "{out}");
    assert!(out.contains("\n1,1,5,0,0,0,0\n"), "{out}");
    let v = values(&out);
    // -1/sqrt(3) correctly rounded (computing 1.0 / 3f64.sqrt() rounds twice, one ulp off).
    assert_eq!(v[0], -0.5773502691896257);
    assert!((v[0] + 1.0 / 3f64.sqrt()).abs() <= f64::EPSILON);
    assert!((v[1] - 1.0 / 6f64.sqrt()).abs() < 1e-16, "{v:?}");
    assert_eq!(&v[2..], [0.0, 0.0]);
}

#[test]
fn wigner3j_errors_name_the_line() {
    let o = hairmath_piped(
        &["wigner3j"],
        "j1,j2,j3,m1,m2,m3\n1,1,0,0,0,0\n1,1,x,0,0,0\n",
    );
    assert_fails_with(&o, &["line 3", "column j3", "\"x\""]);
    assert_eq!(values(&stdout(&o)), [-0.5773502691896257]);
    // An integer j with a half-integer m.
    let o = hairmath_piped(&["wigner3j"], "j1,j2,j3,m1,m2,m3\n1,1,1,1/2,-1/2,0\n");
    assert_fails_with(
        &o,
        &["line 2", "(1 1 1; 1/2 -1/2 0)", "m1 = 0.5", "integer"],
    );
    let o = hairmath_piped(&["wigner3j"], "j1,j2,j3,m1,m2,m3\n1/2,1,1,1/2,0,0\n");
    assert_fails_with(&o, &["line 2", "j1 + j2 + j3 = 2.5"]);
    let o = hairmath_piped(&["wigner3j"], "j1,j2,j3,m1,m2,m3\n1,1,1,1.25,0,0\n");
    assert_fails_with(
        &o,
        &["line 2", "column m1", "not an integer or half-integer"],
    );
    let o = hairmath_piped(&["wigner3j"], "j1,j2,j3,m1,m2\n");
    assert_fails_with(&o, &["line 1", "m3"]);
}

#[test]
fn gaunt_real_and_complex_match_the_library() {
    let rows = [
        (0, 0, 0, 0, 0, 0),
        (1, 1, 1, -1, 2, 0),
        (2, -1, 3, 2, 3, -1),
        (1, 0, 1, 0, 1, 0),
    ];
    let mut input = "id,l1,m1,l2,m2,l3,m3\n".to_string();
    for (k, r) in rows.iter().enumerate() {
        input += &format!("{k},{},{},{},{},{},{}\n", r.0, r.1, r.2, r.3, r.4, r.5);
    }
    for real in [false, true] {
        let o = hairmath_piped(
            if real {
                &["gaunt", "--real"]
            } else {
                &["gaunt"]
            },
            &input,
        );
        assert!(o.status.success(), "stderr: {}", stderr(&o));
        let gaunt = if real { gaunt_real } else { gaunt_complex };
        let want: Vec<f64> = rows
            .iter()
            .map(|r| gaunt(r.0, r.1, r.2, r.3, r.4, r.5).unwrap())
            .collect();
        assert_eq!(values(&stdout(&o)), want, "real: {real}");
        assert!(
            stdout(&o).ends_with(",1,0,1,0,1,0,0\n"),
            "odd l-sum prints 0"
        );
    }
}

#[test]
fn gaunt_malformed_row_is_reported() {
    let o = hairmath_piped(
        &["gaunt"],
        "l1,m1,l2,m2,l3,m3\n1,0,1,0,0,0\n1/2,0,1,0,0,0\n",
    );
    assert_fails_with(
        &o,
        &["line 3", "column l1", "\"1/2\"", "non-negative integer"],
    );
    assert_eq!(stdout(&o).lines().count(), 2);
    let o = hairmath_piped(&["gaunt", "--real"], "l1,m1,l2,m2,l3,m3\n1,0,1,0\n");
    assert_fails_with(&o, &["line 2", "expected 6 fields", "found 4"]);
}

#[test]
fn fit_json_has_the_documented_keys_and_the_library_values() {
    let o = hairmath_piped(&["fit", "--json"], "");
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("valid JSON");
    let rows = rows.as_array().expect("an array");
    let fields = [
        "key",
        "source",
        "approximates",
        "published",
        "refit",
        "metric",
        "published_error",
        "refit_error",
    ];
    for row in rows {
        for field in fields {
            assert!(row.get(field).is_some(), "{field} missing in {row}");
        }
    }
    let refit = |key: &str| {
        rows.iter()
            .find(|r| r["key"] == key)
            .unwrap_or_else(|| panic!("{key} missing"))["refit"]
            .as_f64()
            .unwrap()
    };
    use hairmath::fit::{fit_hg_g, HgReading};
    for deg in [5, 10, 20] {
        let library = fit_hg_g(HgReading::Literal, f64::from(deg).to_radians())
            .unwrap()
            .g;
        let key = format!("gerard.hg_g.literal.beta_{deg}deg");
        assert!((refit(&key) - library).abs() < 1e-12, "{key}");
    }
}

#[test]
fn fit_table_and_bad_eta() {
    let o = hairmath_piped(&["fit"], "");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.starts_with("| constant | source | published | refit | metric |"),
        "{out}"
    );
    assert!(out.contains("gerard.hg_g.literal.beta_10deg"));
    let o = hairmath_piped(&["fit", "--eta", "0.9"], "");
    assert_fails_with(&o, &["eta", "(1, 3]"]);
    let o = hairmath_piped(&["fit", "--details"], "");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    for heading in [
        "## Absorption exponents",
        "## Frostbite Tt attenuation at h = 0.0000 (published)",
        "## Frostbite Trt attenuation at h = 0.8660 (published)",
        "## Frostbite TT Gaussians",
    ] {
        assert!(out.contains(heading), "{heading} missing");
    }
}

/// The message of an invalid value is the library's, whichever subcommand takes it.
#[test]
fn an_invalid_value_gives_the_same_message_in_every_subcommand() {
    let dir = std::env::temp_dir().join(format!("hairmath-cli-params-{}", std::process::id()));
    let out = dir.to_str().expect("a UTF-8 path");
    let beta_n = "beta_n = 1.5 is not allowed: the azimuthal roughness must be in [1e-16, 1]";
    let eta = "eta = 5 is not allowed: the relative index of refraction must be in (1, 3]";
    let sigma_a =
        "sigma_a = -1 is not allowed: absorption must be finite and >= 0 in every channel";
    let lut = |kind: &str, rest: &str| format!("lut --kind {kind} {rest} --out {out}");
    let cases = [
        (
            "eval --beta-m 0.3 --beta-n 1.5 --sigma-a 1".to_string(),
            beta_n,
        ),
        (
            "eval --model chiang-far --beta-m 0.3 --beta-n 1.5 --sigma-a 1".into(),
            beta_n,
        ),
        (lut("far-field", "--beta-n-range 0.2,1.5"), beta_n),
        (
            "eval --beta-m 0.3 --beta-n 0.3 --sigma-a 1 --eta 5".into(),
            eta,
        ),
        ("eval --model marschner --sigma-a 1 --eta 5".into(), eta),
        (lut("gerard", "--eta 5"), eta),
        ("fit --eta 5".into(), eta),
        (lut("nguyen-n", "--sigma-a -1"), sigma_a),
    ];
    for (args, message) in cases {
        let args: Vec<&str> = args.split_whitespace().collect();
        let o = hairmath_piped(&args, &format!("{HEADER}\n"));
        assert_fails_with(&o, &[message]);
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn flags_of_other_models_and_missing_flags_are_named() {
    let o = hairmath_piped(
        &[
            "eval",
            "--model",
            "marschner",
            "--sigma-a",
            "1",
            "--beta-m",
            "0.3",
        ],
        "",
    );
    assert_fails_with(
        &o,
        // --beta-n also belongs to karis-refit (its colour inversion).
        &["--beta-m and --alpha-deg apply only to --model chiang, chiang-far"],
    );
    let o = hairmath_piped(
        &[
            "eval",
            "--model",
            "chiang",
            "--beta-m",
            "0.3",
            "--sigma-a",
            "1",
        ],
        "",
    );
    assert_fails_with(&o, &["--model chiang requires --beta-n"]);
    let o = hairmath_piped(&["eval", "--model", "nonsense"], "");
    assert!(!o.status.success());
    assert!(stderr(&o).contains("chiang-far"), "{}", stderr(&o));
}

#[test]
fn marschner_matches_the_library() {
    use hairmath::bcsdf::Marschner2003;
    use hairmath::params::MarschnerLobes;
    let o = eval_model("marschner", &["--sigma-a", "0.5,0.8,1.4"], &far_input());
    assert!(o.status.success(), "stderr: {}", stderr(&o));
    let model = Marschner2003 {
        lobes: MarschnerLobes::default(),
        eta: RefractiveIndex::new(1.55).unwrap(),
        sigma_a: Absorption::new([0.5, 0.8, 1.4]).unwrap(),
        caustic: Some(hairmath::azimuthal::CausticParams::default()),
    };
    for (line, (wi, wo)) in stdout(&o).lines().skip(1).zip(FAR_ROWS) {
        assert_eq!(
            appended(line),
            model.eval(&Query::far(unit(wi), unit(wo))),
            "{line}"
        );
    }
}

/// `hairmath eval --model MODEL` with `flags` only.
fn eval_model(model: &str, flags: &[&str], stdin: &str) -> Output {
    let mut args = vec!["eval", "--model", model];
    args.extend(flags);
    hairmath_piped(&args, stdin)
}
