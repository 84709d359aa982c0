//! The `.hair` reader ([`hairmath::strands::hair_file::read_hair`]) on arbitrary bytes: no
//! panic, and a file it reads holds no more points than its bytes can store (12 bytes a point)
//! and writes back to bytes that read to the same strands.
#![no_main]

use hairmath::strands::hair_file::{read_hair, write_hair};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(file) = read_hair(data) {
        assert!(file.strands.point_count() * 12 <= data.len());
        let bytes = write_hair(&file).expect("a file read can be written");
        let again = read_hair(&bytes).expect("a file written can be read");
        assert_eq!(again.strands, file.strands);
    }
});
