//! The JSON reader must return Ok or Error::Input on any bytes, never panic; what it accepts must
//! re-validate, and write back to JSON that reads again.
#![no_main]
use libfuzzer_sys::fuzz_target;
use slice2solid::io::json::{parse_json, to_json_string};
use slice2solid::validate::validate;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(s) = parse_json(&text, "fuzz.json") {
        let s = validate(s, "fuzz").expect("accepted sections re-validate");
        parse_json(&to_json_string(&s), "again.json").expect("written JSON reads back");
    }
});
