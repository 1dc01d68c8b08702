//! The `.xyz` point format of `slice2solid delaunay`: one `x y z` per line (blank lines and lines
//! starting with `#` are skipped).
use crate::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

pub fn parse_xyz(text: &str, name: &str) -> Result<Vec<[f64; 3]>> {
    let mut pts = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let loc = || format!("{name}:{}", k + 1);
        let mut it = line.split_ascii_whitespace();
        let mut p = [0.0; 3];
        for c in p.iter_mut() {
            let tok = it
                .next()
                .ok_or_else(|| Error::input(loc(), "expected three coordinates `x y z`"))?;
            *c = tok
                .parse::<f64>()
                .map_err(|_| Error::input(loc(), format!("`{tok}` is not a number")))?;
            if !c.is_finite() {
                return Err(Error::input(
                    loc(),
                    format!("non-finite coordinate `{tok}`"),
                ));
            }
        }
        if it.next().is_some() {
            return Err(Error::input(loc(), "more than three values on the line"));
        }
        pts.push(p);
    }
    Ok(pts)
}

pub fn read_xyz(path: &Path) -> Result<Vec<[f64; 3]>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse_xyz(&text, &path.display().to_string())
}

/// Writes points with full precision (`{:?}` prints the shortest string that round-trips).
pub fn write_xyz(path: &Path, pts: &[[f64; 3]]) -> Result<()> {
    let mut s = String::with_capacity(pts.len() * 60);
    for p in pts {
        let _ = writeln!(s, "{:?} {:?} {:?}", p[0], p[1], p[2]);
    }
    std::fs::write(path, s).map_err(|e| Error::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn parse_and_errors() {
        let p = parse_xyz("# c\n1 2 3\n\n4.5 -1e3 0\n", "f").unwrap();
        assert_eq!(p, vec![[1.0, 2.0, 3.0], [4.5, -1000.0, 0.0]]);
        let e = parse_xyz("1 2 3\n1 2\n", "f").unwrap_err().to_string();
        assert!(e.starts_with("f:2:"), "{e}");
        assert!(parse_xyz("1 2 x", "f").is_err());
        assert!(parse_xyz("1 2 NaN", "f").is_err());
        assert!(parse_xyz("1 2 3 4", "f").is_err());
    }
}
