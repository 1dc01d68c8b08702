//! The CSL reader must return Ok or Error::Input on any bytes, never panic; what it accepts must
//! re-validate, and write back to CSL that reads again.
#![no_main]
use libfuzzer_sys::fuzz_target;
use slice2solid::io::csl::{parse_csl, to_csl_string};
use slice2solid::validate::validate;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(s) = parse_csl(&text, "fuzz.csl") {
        let s = validate(s, "fuzz").expect("accepted sections re-validate");
        parse_csl(&to_csl_string(&s), "again.csl").expect("written CSL reads back");
    }
});
