//! `hairmath wigner3j`'s CSV reader and the half-integer arguments
//! ([`hairmath::csv::wigner3j_filter`]) on arbitrary bytes: no panic, the output no longer than
//! the input plus one appended value per line.
#![no_main]

use hairmath::csv::wigner3j_filter;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut out = Vec::new();
    let _ = wigner3j_filter(data, &mut out);
    let lines = data.iter().filter(|&&b| b == b'\n' || b == b'\r').count() + 1;
    assert!(out.len() <= data.len() + lines * 32, "{} bytes out of {}", out.len(), data.len());
});
