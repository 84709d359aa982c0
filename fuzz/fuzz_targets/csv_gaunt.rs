//! `hairmath gaunt`'s CSV reader ([`hairmath::csv::gaunt_filter`]) on arbitrary bytes, complex
//! or real coefficients by the first byte's low bit: no panic, the output no longer than the
//! input plus one appended value per line.
#![no_main]

use hairmath::csv::gaunt_filter;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&first, data)) = data.split_first() else {
        return;
    };
    let mut out = Vec::new();
    let _ = gaunt_filter(data, &mut out, first & 1 == 1);
    let lines = data.iter().filter(|&&b| b == b'\n' || b == b'\r').count() + 1;
    assert!(out.len() <= data.len() + lines * 32, "{} bytes out of {}", out.len(), data.len());
});
