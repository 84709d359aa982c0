//! Issue 17, the library's side: no panic, no NaN and no unbounded work on any input the crate
//! accepts. Each test names the item of the issue it pins; each fails on the code before the
//! issue was fixed (which accepted, returned or computed what is asserted against here).

use std::time::{Duration, Instant};

use hairmath::absorption::{Absorption, MAX_MELANIN};
use hairmath::bcsdf::{
    eval_batch, BatchError, BatchReal, Bcsdf, ChiangHair, HostBatch, InputValue, InstructionSet,
    Model, Query, SampledBcsdf, UNIT_TOLERANCE,
};
use hairmath::fresnel::fresnel_dielectric;
use hairmath::geometry::{FibreFrame, V3};
use hairmath::lobe::{i0, log_i0, log_i0e};
use hairmath::lut::{
    bake, lookup_error, Axis, FarFieldN, LutError, NguyenM, Table, FAR_FIELD_MAX_EVALUATIONS,
    MAX_EVALUATIONS,
};
use hairmath::models::{gerard_hg_g, HG_G_BETA_DOMAIN};
use hairmath::params::{
    AzimuthalRoughness, HairParams, LongitudinalRoughness, MarschnerLobes, RefractiveIndex,
    MIN_BETA,
};
use hairmath::plan::{Scene, MAX_SCENE_BYTES};
use hairmath::quadrature::gauss_legendre;
use hairmath::registry::MODELS;
use hairmath::sh::{index_to_lm, project, sh_index, GauntTensor, MAX_PROJECT_LMAX};
use hairmath::ParamError;

/// Unit directions spread over the sphere (a Fibonacci lattice) and the hard ones of
/// docs/ARCHITECTURE.md: along the tangent both ways, perpendicular, grazing.
fn directions() -> Vec<V3<f64>> {
    let n = 48;
    let mut v: Vec<V3<f64>> = (0..n)
        .map(|k| {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / n as f64;
            let phi = k as f64 * 2.399_963_229_728_653;
            let r = (1.0 - z * z).sqrt();
            V3::new(z, r * phi.cos(), r * phi.sin())
        })
        .collect();
    let grazing = (1.0 - 1e-12_f64).sqrt();
    v.extend([
        V3::new(1.0, 0.0, 0.0),
        V3::new(-1.0, 0.0, 0.0),
        V3::new(0.0, 1.0, 0.0),
        V3::new(0.0, 0.0, -1.0),
        V3::new(grazing, 1e-6, 0.0),
    ]);
    v
}

/// Every query of [`directions`] pairs (each with the next but three, itself and its opposite)
/// at offsets -1, 0, 0.5 and 1.
fn queries() -> Vec<Query<f64>> {
    let d = directions();
    let mut q = Vec::new();
    for (k, &wi) in d.iter().enumerate() {
        for wo in [d[(k + 3) % d.len()], wi, wi.scale(-1.0)] {
            for h in [-1.0, 0.0, 0.5, 1.0] {
                q.push(Query::new(wi, wo, h));
            }
        }
    }
    q
}

fn to_f32(q: &Query<f64>) -> Query<f32> {
    let v = |w: V3<f64>| V3::new(w.x as f32, w.y as f32, w.z as f32);
    Query::new(v(q.wi), v(q.wo), q.h as f32)
}

fn assert_finite<T: Into<f64> + Copy>(what: &str, s: &[T], q: &Query<f64>) {
    for &x in s {
        let x: f64 = x.into();
        assert!(x.is_finite() && x >= 0.0, "{what}: {x} at {q:?}");
    }
}

/// Item 2: every registered model with a roughness stays finite and non-negative at the
/// smallest accepted roughness, in `f64`, in `f32` as the CPU instantiates it and as the shader
/// computes it from varying roughness, and in SIMD lanes; below it the roughness is refused with
/// the domain in the message (before, 1e-200 was accepted and S was NaN).
#[test]
fn the_smallest_accepted_roughness_is_finite_in_every_precision() {
    let queries = queries();
    let mut checked = 0;
    for entry in MODELS {
        let names: Vec<&str> = entry.inputs.iter().map(|i| i.name).collect();
        let rough: Vec<&str> = ["beta_m", "beta_n"]
            .into_iter()
            .filter(|n| names.contains(n))
            .collect();
        if rough.is_empty() {
            continue;
        }
        let mut values = entry.example_values();
        for name in &rough {
            values.set(name, InputValue::Number(MIN_BETA));
        }
        let model = (entry.build)(&values).unwrap_or_else(|e| panic!("{}: {e}", entry.name));
        for q in &queries {
            assert_finite(entry.name, &model.eval(q), q);
        }
        if let Some(shader) = &entry.shader {
            let cpu = (shader.cpu)(&values, &rough, None)
                .unwrap_or_else(|e| panic!("{}: {e}", entry.name));
            for q in &queries {
                let q32 = to_f32(q);
                assert_finite(entry.name, &cpu.shader.eval(&q32), q);
                assert_finite(entry.name, &cpu.rounded.eval(&q32), q);
            }
        }
        for name in &rough {
            let mut below = values.clone();
            below.set(name, InputValue::Number(MIN_BETA / 2.0));
            let message = (entry.build)(&below).err().expect("refused").to_string();
            assert!(message.contains("[1e-16, 1]"), "{}: {message}", entry.name);
        }
        checked += 1;
    }
    assert!(checked >= 5, "only {checked} models have a roughness");

    // The Chiang model in SIMD lanes and its pdf.
    let params = HairParams {
        beta_m: LongitudinalRoughness::new(MIN_BETA).unwrap(),
        beta_n: AzimuthalRoughness::new(MIN_BETA).unwrap(),
        ..HairParams::default()
    };
    let chiang = ChiangHair::<f64>::new(&params);
    let lanes = Model::instantiate::<BatchReal>(&chiang);
    let (mut wi, mut wo, mut h) = (Vec::new(), Vec::new(), Vec::new());
    for q in &queries {
        let q = to_f32(q);
        wi.push([q.wi.x, q.wi.y, q.wi.z]);
        wo.push([q.wo.x, q.wo.y, q.wo.z]);
        h.push(q.h);
    }
    let mut out = vec![[0.0_f32; 3]; wi.len()];
    eval_batch(&lanes, &wi, &wo, &h, &mut out).unwrap();
    for (s, q) in out.iter().zip(&queries) {
        assert_finite("chiang SIMD", s, q);
    }
    for set in InstructionSet::ALL.into_iter().filter(|s| s.is_supported()) {
        HostBatch::on(set, &chiang)
            .eval(&wi, &wo, &h, &mut out)
            .unwrap();
        for (s, q) in out.iter().zip(&queries) {
            assert_finite(&format!("chiang on {set:?}"), s, q);
        }
    }
    for q in &queries {
        let p = chiang.pdf(q);
        assert!(p.is_finite() && p >= 0.0, "pdf {p} at {q:?}");
    }
    for beta in [1e-200, 2e-154, 1.5e-19, MIN_BETA * 0.999_999] {
        assert!(LongitudinalRoughness::new(beta).is_err(), "{beta}");
        assert!(AzimuthalRoughness::new(beta).is_err(), "{beta}");
    }
}

/// Item 4: the Bessel functions at the largest finite arguments and at infinity.
#[test]
fn bessel_functions_are_finite_up_to_the_largest_argument() {
    for x in [1e30, 1e100, 1e300, 1e308, f64::MAX] {
        assert!(log_i0e(x).is_finite() && log_i0e(x) < 0.0, "{x}");
        assert_eq!(log_i0(x), x, "ln I0(x) = x - 0.5 ln(2 pi x) rounds to x");
        assert_eq!(i0(x), f64::INFINITY);
    }
    for x in [1e30_f32, f32::MAX] {
        assert!(log_i0e(x).is_finite(), "{x}");
        assert!(log_i0(x).is_finite(), "{x}");
    }
    assert_eq!(log_i0(f64::INFINITY), f64::INFINITY);
    assert_eq!(log_i0e(f64::INFINITY), f64::NEG_INFINITY);
    assert_eq!(i0(f64::INFINITY), f64::INFINITY);
}

/// Runs `f` and returns its result and how long it took.
fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let start = Instant::now();
    let value = f();
    (value, start.elapsed())
}

/// Item 5: work a caller can ask for is capped with a typed error, at once, or fast.
#[test]
fn uncapped_work_is_refused_at_once_or_fast() {
    let far = FarFieldN::new(
        RefractiveIndex::HUMAN_HAIR,
        Absorption::new([0.5; 3]).unwrap(),
        AzimuthalRoughness::new(0.2).unwrap(),
        AzimuthalRoughness::new(0.8).unwrap(),
        1e-6,
    )
    .unwrap();
    let (result, took) = timed(|| bake(&far, &[512, 512, 64]));
    match result {
        Err(LutError::TooMuchWork { asked, max, .. }) => {
            assert_eq!((asked, max), (512 * 512 * 64, FAR_FIELD_MAX_EVALUATIONS));
        }
        other => panic!("{:?}", other.map(|t| t.axes().len())),
    }
    assert!(took < Duration::from_millis(100), "{took:?}");

    let nguyen = NguyenM::new(MarschnerLobes::default());
    let table = bake(&nguyen, &[8, 8]).unwrap();
    let (result, took) = timed(|| lookup_error(&nguyen, &table, 1_000_000_000));
    let message = result.unwrap_err().to_string();
    assert!(
        message.contains(&format!("at most {MAX_EVALUATIONS} error points")),
        "{message}"
    );
    assert!(took < Duration::from_millis(100), "{took:?}");
    assert!(matches!(
        bake(&nguyen, &[5000, 5000]),
        Err(LutError::TooMuchWork { .. })
    ));

    // A scene file is read up to its limit, not without end.
    let (result, took) = timed(|| Scene::read(std::path::Path::new("/dev/zero")));
    let message = result.unwrap_err().to_string();
    assert!(
        message.contains(&format!("longer than {MAX_SCENE_BYTES} bytes")),
        "{message}"
    );
    assert!(took < Duration::from_secs(1), "{took:?}");

    let (result, took) = timed(|| project(200, |_| 1.0));
    assert!(result.is_err() && took < Duration::from_millis(100));
    assert!(project(MAX_PROJECT_LMAX + 1, |_| 1.0).is_err());
    let (result, took) = timed(|| GauntTensor::new(40));
    assert!(result.is_err() && took < Duration::from_millis(100));

    // Gauss-Legendre is O(n): a million nodes in well under the O(n^2) method's hours.
    let (rule, took) = timed(|| gauss_legendre(1_000_000));
    assert!(took < Duration::from_secs(5), "{took:?}");
    let sum: f64 = rule.iter().map(|&(_, w)| w).sum();
    let second: f64 = rule.iter().map(|&(x, w)| w * x * x).sum();
    assert!((sum - 2.0).abs() < 1e-12 && (second - 2.0 / 3.0).abs() < 1e-12);
    assert!(rule.windows(2).all(|p| p[0].0 > p[1].0), "nodes decrease");
}

/// Item 6: bad directions, NaN and lookups give a typed error or NaN, never a number.
#[test]
fn bad_inputs_do_not_silently_give_numbers() {
    let (wi, wo) = (V3::new(0.0, 1.0, 0.0), V3::new(0.0, 0.6, 0.8));
    assert!(Query::checked(wi, wo, 0.0).is_ok());
    for bad in [
        V3::new(0.0, 2.0, 0.0),
        V3::new(0.0, 0.0, 0.0),
        V3::new(f64::NAN, 1.0, 0.0),
        V3::new(f64::INFINITY, 0.0, 0.0),
    ] {
        let e = Query::checked(bad, wo, 0.0).unwrap_err();
        assert!(
            matches!(
                e,
                ParamError::NotUnit { name: "wi", .. } | ParamError::BadVector { name: "wi", .. }
            ),
            "{e}"
        );
        assert!(Query::checked(wi, bad, 0.0).is_err());
    }
    assert!(Query::checked(wi, wo, f64::NAN).is_err());
    assert!(Query::checked(wi, wo, 1.5).is_err());
    // Within the tolerance a direction is normalised: S is that of the unit direction.
    let model = ChiangHair::<f64>::new(&HairParams::default());
    let nearly = Query::checked(wi.scale(1.0 + 0.5 * UNIT_TOLERANCE), wo, 0.0).unwrap();
    assert_eq!(model.eval(&nearly), model.eval(&Query::new(wi, wo, 0.0)));

    // The batch refuses a direction of length 2 (which halved S) naming the sample.
    let lanes = Model::instantiate::<BatchReal>(&model);
    let mut out = [[0.0_f32; 3]; 2];
    let err = eval_batch(
        &lanes,
        &[[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]],
        &[[0.0, 0.6, 0.8]; 2],
        &[0.0; 2],
        &mut out,
    )
    .unwrap_err();
    assert!(matches!(
        err,
        BatchError::Direction {
            index: 1,
            name: "wi",
            ..
        }
    ));

    assert!(fresnel_dielectric(f64::NAN, 1.55).is_nan());
    assert!(fresnel_dielectric(0.5, f64::NAN).is_nan());
    // gerard_hg_g is a hot path: NaN is documented to count as the domain's lower end.
    assert_eq!(gerard_hg_g(f64::NAN), gerard_hg_g(HG_G_BETA_DOMAIN.0));
    assert_eq!(
        gerard_hg_g(f32::NAN),
        gerard_hg_g(HG_G_BETA_DOMAIN.0 as f32)
    );

    let table = Table::new(
        vec![
            Axis::new("x", 0.0, 1.0, 2).unwrap(),
            Axis::new("y", 0.0, 1.0, 2).unwrap(),
        ],
        vec!["v".to_string()],
        vec![0.0, 1.0, 2.0, 3.0],
    )
    .unwrap();
    let err = table.lookup(&[0.5, f32::NAN]).unwrap_err();
    assert!(
        matches!(&err, LutError::Coordinate { axis } if axis == "y"),
        "{err}"
    );
    // x is the fastest axis: (x max, y min) is the second value.
    assert_eq!(table.lookup(&[f32::INFINITY, 0.0]).unwrap(), [1.0]);
}

/// Item 7: the integer helpers refuse what is outside their domain.
#[test]
fn integer_helpers_refuse_indices_outside_their_domain() {
    assert!(sh_index(0, -5).is_err());
    assert!(sh_index(3, 4).is_err());
    assert!(sh_index(usize::MAX, 0).is_err());
    assert_eq!(sh_index(2, -1), Ok(5));
    assert!(index_to_lm(usize::MAX).is_err());
    assert!(index_to_lm(1 << 62).is_err());
    for index in (0..10_000).chain([(1 << 62) - 1, (1 << 61) + 12_345]) {
        let (l, m) = index_to_lm(index).unwrap();
        assert!(m.unsigned_abs() <= l, "{index}");
        assert_eq!(sh_index(l as usize, m as isize), Ok(index));
    }
    let e = Absorption::from_melanin(1e308, 1e308)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("eumelanin = 1e308") && e.contains("[0, 1e300]"),
        "{e}"
    );
    let most = Absorption::from_melanin(MAX_MELANIN, MAX_MELANIN).unwrap();
    assert!(most.rgb().iter().all(|c| c.is_finite()));
}

/// Item 8 (the library's messages): numbers in exponent form where shorter, and a long finite
/// tangent accepted.
#[test]
fn messages_say_what_was_wrong() {
    let e = LongitudinalRoughness::new(1e308).unwrap_err().to_string();
    assert_eq!(
        e,
        "beta_m = 1e308 is not allowed: the longitudinal roughness must be in [1e-16, 1]"
    );
    let e = Query::checked(V3::new(0.0, 1e-90, 0.0), V3::new(0.0, 1.0, 0.0), 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("wi = (0, 1e-90, 0) has length 1e-90"), "{e}");
    let (r2, r3) = (0.5_f64.sqrt(), (1.0_f64 / 3.0).sqrt());
    for (tangent, unit) in [
        (
            glam::DVec3::new(1e300, 1e300, 0.0),
            glam::DVec3::new(r2, r2, 0.0),
        ),
        (
            glam::DVec3::new(-1e-300, 0.0, 1e-300),
            glam::DVec3::new(-r2, 0.0, r2),
        ),
        (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(r3)),
    ] {
        let t = FibreFrame::new(tangent).unwrap().tangent;
        assert!((t - unit).length() < 1e-15, "{tangent}: {t}");
    }
    assert!(FibreFrame::new(glam::DVec3::ZERO).is_err());
    assert!(FibreFrame::new(glam::DVec3::new(f64::INFINITY, 0.0, 0.0)).is_err());
}
