//! Warnings on the terminal: a large input can give hundreds of the same kind (one per flat zone),
//! so each kind (its text with the numbers masked) is shown a few times, then counted; the report
//! keeps them all.
use std::collections::HashMap;

/// Warnings shown per kind before the rest are counted.
pub const SHOWN_PER_KIND: usize = 3;

/// `text` with every number (digits, with sign, decimal point and exponent) replaced by `#`.
fn kind(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() {
            while i < b.len()
                && (b[i].is_ascii_digit()
                    || b[i] == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit)
                    || (b[i] == b'e' || b[i] == b'E')
                        && b.get(i + 1)
                            .is_some_and(|c| c.is_ascii_digit() || *c == b'-' || *c == b'+'))
            {
                i += if b[i] == b'e' || b[i] == b'E' { 2 } else { 1 };
            }
            out.push('#');
        } else {
            // text is UTF-8: copy whole characters
            let c = text[i..].chars().next().unwrap_or(' ');
            out.push(c);
            i += c.len_utf8();
        }
    }
    out
}

/// The lines to print for `warnings`, in their order: all of them with `all`, else the first
/// [`SHOWN_PER_KIND`] of each kind and, after the last shown one of a kind, how many more there are.
/// `report` is where the full list went (if anywhere).
pub fn lines(warnings: &[String], all: bool, report: Option<&std::path::Path>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    if all {
        out.extend(warnings.iter().map(|w| format!("warning: {w}")));
        return out;
    }
    let kinds: Vec<String> = warnings.iter().map(|w| kind(w)).collect();
    let mut total: HashMap<&str, usize> = HashMap::new();
    for k in &kinds {
        *total.entry(k).or_default() += 1;
    }
    let mut seen: HashMap<&str, usize> = HashMap::new();
    let full = match report {
        Some(p) => format!("all in {}", p.display()),
        None => "all with --all-warnings or in --report".to_string(),
    };
    for (w, k) in warnings.iter().zip(&kinds) {
        let n = seen.entry(k).or_default();
        *n += 1;
        if *n <= SHOWN_PER_KIND {
            out.push(format!("warning: {w}"));
            let rest = total[k.as_str()] - SHOWN_PER_KIND;
            if *n == SHOWN_PER_KIND && rest > 0 {
                out.push(format!(
                    "warning: ... and {rest} more like the one above ({full})"
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zone(face: u32, area: &str) -> String {
        format!("face {face} (plane 3): flat zone of area {area} attached from neither side, thickened into cell 7 (paper Fig. 12c; slab 5.90e-5..5.90e-5 thick)")
    }

    #[test]
    fn numbers_are_masked() {
        assert_eq!(
            kind("face 12 (plane 3): area 2.7204e-6, slab 1.47e-5..5.90e-5 thick"),
            "face # (plane #): area #, slab #..# thick"
        );
        assert_eq!(kind("x.csl:39: plane 1"), "x.csl:#: plane #");
        assert_eq!(kind("δ up to 5.90e-7"), "δ up to #");
    }

    #[test]
    fn each_kind_is_shown_three_times_then_counted() {
        let mut w: Vec<String> = (0..10)
            .map(|f| zone(f, &format!("{}.5e-{}", f, f + 1)))
            .collect();
        w.insert(
            4,
            "tetrahedral mesh is non-conforming across 57 faces".into(),
        );
        w.push("face 99 (plane 2): flat zone of area 1e-3 attached from neither side, not thickened (3 crossings with δ up to 5.90e-7 (0 before)): not in the solid".into());
        let l = lines(&w, false, None);
        assert_eq!(l.len(), 3 + 1 + 1 + 1, "{l:#?}");
        assert_eq!(l[0], format!("warning: {}", zone(0, "0.5e-1")));
        assert!(l[3].contains("and 7 more like the one above"), "{}", l[3]);
        assert!(l[4].contains("non-conforming across 57 faces"));
        assert!(l[5].contains("not thickened"));
        let l = lines(&w, false, Some(std::path::Path::new("r.json")));
        assert!(l[3].ends_with("(all in r.json)"), "{}", l[3]);
        assert_eq!(lines(&w, true, None).len(), w.len());
    }

    #[test]
    fn few_warnings_are_all_shown() {
        let w: Vec<String> = (0..3).map(|f| zone(f, "1.0")).collect();
        assert_eq!(lines(&w, false, None).len(), 3);
    }
}
