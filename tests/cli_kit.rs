//! `hairmath cases` and `hairmath check` end to end, as a renderer in another language uses
//! them: the cases written in each convention, evaluated by "the renderer" (here hairmath's
//! own model through `Convention`, once correctly and once with pbrt's cosine left out), and
//! checked: PASS with status 0, FAIL with status 1 naming the worst rows, typed errors for bad
//! input.

use hairmath::bcsdf::{Bcsdf, ChiangHair};
use hairmath::glam::DVec3;
use hairmath::params::HairParams;
use hairmath::testing::{Convention, ConventionQuery};

mod piped;
use piped::hairmath_piped;

/// The CSV of `cases` with a renderer's f appended: hairmath's S converted to `convention`'s
/// f, times `scale` (1 for a correct renderer).
fn render(cases: &str, convention: Convention, scale: impl Fn(&ConventionQuery) -> f64) -> String {
    let hair = ChiangHair::<f64>::new(&HairParams::default());
    let mut lines = cases.lines();
    let mut out = format!("{},f_r,f_g,f_b\n", lines.next().expect("a header"));
    for line in lines {
        let v: Vec<f64> = line
            .split(',')
            .map(|f| f.parse().expect("a number"))
            .collect();
        let foreign = ConventionQuery {
            wi: DVec3::new(v[0], v[1], v[2]),
            wo: DVec3::new(v[3], v[4], v[5]),
            h: v.get(6).copied(),
        };
        let query = convention
            .to_hairmath(&foreign)
            .expect("the cases are valid");
        let f = convention.f_of_s(hair.eval(&query), &query);
        let k = scale(&foreign);
        out += &format!("{line},{},{},{}\n", f[0] * k, f[1] * k, f[2] * k);
    }
    out
}

#[test]
fn a_correct_renderer_passes_in_every_convention() {
    for (convention, name) in Convention::ALL {
        let cases = hairmath_piped(&["cases", "--count", "300", "--convention", name], "");
        assert!(cases.status.success());
        let cases = String::from_utf8(cases.stdout).expect("UTF-8");
        assert_eq!(cases.lines().count(), 1 + 243 + 300, "{name}");
        let header = cases.lines().next().expect("a header");
        assert_eq!(
            header.ends_with(",h"),
            convention.has_offset(),
            "{name}: {header}"
        );
        let values = render(&cases, convention, |_| 1.0);
        let check = hairmath_piped(&["check", "--convention", name, "--json"], &values);
        let stdout = String::from_utf8_lossy(&check.stdout);
        assert!(check.status.success(), "{name}: {stdout}");
        let json: serde_json::Value = serde_json::from_str(&stdout).expect("JSON");
        assert_eq!(json["rows"], 543);
        assert_eq!(json["passes"], true);
        // Written with shortest round-trip numbers: the values come back to rounding.
        assert!(
            json["max_rel_error"].as_f64().expect("a number") < 1e-12,
            "{name}: {json}"
        );
    }
}

#[test]
fn a_renderer_that_forgets_pbrts_cosine_fails_with_status_1() {
    let cases = hairmath_piped(&["cases", "--count", "200", "--convention", "pbrt"], "");
    let cases = String::from_utf8(cases.stdout).expect("UTF-8");
    // pbrt's f is S / |wi.z|; this renderer returns S.
    let values = render(&cases, Convention::Pbrt, |q| {
        q.wi.z.abs().max(f64::MIN_POSITIVE)
    });
    let check = hairmath_piped(&["check", "--convention", "pbrt", "--worst", "2"], &values);
    assert_eq!(check.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&check.stdout);
    assert!(
        stdout.contains("FAIL") && stdout.contains("row "),
        "{stdout}"
    );
    let stderr = String::from_utf8_lossy(&check.stderr);
    assert!(stderr.contains("check failed"), "{stderr}");
}

#[test]
fn bad_input_is_a_typed_error() {
    let bad = [
        ("wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h\n", "f_r"),
        (
            "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h,f_r,f_g,f_b\n0,2,0,0,1,0,0,1,1,1\n",
            "length",
        ),
        (
            "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h,f_r,f_g,f_b\n0,1,0,0,1,0,0,x,1,1\n",
            "not a number",
        ),
    ];
    for (input, expected) in bad {
        let check = hairmath_piped(&["check"], input);
        assert_eq!(check.status.code(), Some(2), "{input}");
        let stderr = String::from_utf8_lossy(&check.stderr);
        assert!(stderr.contains(expected), "{input}: {stderr}");
    }
    // Directions along the normal (Mitsuba's +Y is the tangent, where only finiteness is
    // checked).
    let mitsuba_h = "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,h,f_r,f_g,f_b\n0,0,1,0,0,1,0,1,1,1\n";
    let check = hairmath_piped(&["check", "--convention", "mitsuba"], mitsuba_h);
    // Mitsuba's columns have no h: the extra column passes through unread.
    assert_eq!(check.status.code(), Some(1));
    let negative = hairmath_piped(&["check", "--tolerance", "-1"], "");
    assert_eq!(negative.status.code(), Some(2));
    let too_many = hairmath_piped(&["cases", "--count", "2000000"], "");
    assert_eq!(too_many.status.code(), Some(2));
}
