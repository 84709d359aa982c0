use hairmath::bcsdf::*;
use hairmath::diagnostics::*;
use hairmath::fit::*;
use hairmath::registry::find_model;
#[test]
fn scratch() {
    let settings = ComparisonSettings::brown();
    let hair = settings.hairs[0].params().unwrap();
    let reference = ReferenceSamples::new(
        &ChiangFarField::<f64>::with_rule(&hair, &FarFieldRule::gauss_legendre(64).unwrap()),
        DirectionPairs::kronecker(1 << 14),
    );
    for name in ["kajiya-kay", "tressfx", "scheuermann"] {
        let entry = find_model(name).unwrap();
        let a = entry.approximation.unwrap();
        let start = (a.mapped_inputs)(&hair);
        let t = std::time::Instant::now();
        let fit = fit_model_inputs(entry, a.fitted_inputs, &start, &reference).unwrap();
        println!(
            "{name}: {:?} iters {} E {:?} in {:?}",
            fit.minimum.params,
            fit.minimum.iterations,
            fit.error,
            t.elapsed()
        );
        let loss =
            |x: &[f64]| input_loss(entry, &inputs_at(&start, a.fitted_inputs, x), &reference);
        let at = loss(&fit.minimum.params);
        for i in 0..fit.minimum.params.len() {
            let step = 1e-2 * fit.minimum.params[i].abs().max(1e-3);
            let mut m = fit.minimum.params.clone();
            m[i] -= step;
            let lo = loss(&m) - at;
            m[i] += 2.0 * step;
            let hi = loss(&m) - at;
            println!("  {i}: -{lo:.3e} +{hi:.3e}");
        }
    }
}
