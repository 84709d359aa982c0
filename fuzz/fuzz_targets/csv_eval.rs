//! `hairmath eval`'s CSV reader and evaluation ([`hairmath::csv::eval_filter`]) on arbitrary
//! bytes, for a far-field and a near-field model: no panic, every value printed finite, the
//! output no longer than the input plus one appended value triple per line.
#![no_main]

use hairmath::bcsdf::ChiangHair;
use hairmath::csv::eval_filter;
use hairmath::params::HairParams;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let near = ChiangHair::<f64>::new(&HairParams::default());
    let mut out = Vec::new();
    let _ = eval_filter(&near, data, &mut out);
    let lines = data.iter().filter(|&&b| b == b'\n' || b == b'\r').count() + 1;
    assert!(out.len() <= data.len() + lines * 80, "{} bytes out of {}", out.len(), data.len());
    let text = String::from_utf8(out).expect("the output is UTF-8");
    for line in text.lines().skip(1) {
        for value in line.rsplit(',').take(3) {
            let v: f64 = value.parse().expect("an appended value");
            assert!(v.is_finite() && v >= 0.0, "{line}");
        }
    }
});
