//! TetGen 1.5 as an oracle (cargo feature `tetgen`): Delaunay tetrahedralization of a point set,
//! through our C++ shim `native/tetgen_shim.cpp`. Tetrahedra are returned positively oriented
//! (the kernel's convention, see [`super::pred::orient`]) as indices into the input points.
use super::pred;
use std::os::raw::c_int;

extern "C" {
    fn s2s_tetgen_delaunay(
        xyz: *const f64,
        n: c_int,
        tets: *mut *mut c_int,
        ntets: *mut c_int,
        quiet: c_int,
    ) -> c_int;
    fn s2s_tetgen_free(p: *mut c_int);
}

/// Delaunay tetrahedra of `points` computed by TetGen (`tetrahedralize("Q")`, no Steiner points).
/// Duplicate points are left out of every tetrahedron. Fewer than 4 points, or coplanar input,
/// give an empty list.
pub fn tetgen_delaunay(points: &[[f64; 3]]) -> crate::Result<Vec<[u32; 4]>> {
    if points.len() < 4 {
        return Ok(Vec::new());
    }
    if points.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(crate::Error::input("points", "non-finite coordinate"));
    }
    let n = c_int::try_from(points.len())
        .map_err(|_| crate::Error::input("points", "too many points for TetGen"))?;
    let mut ptr: *mut c_int = std::ptr::null_mut();
    let mut m: c_int = 0;
    // SAFETY: the shim reads 3n doubles from a live slice and writes an owned malloc'ed array.
    let code =
        unsafe { s2s_tetgen_delaunay(points.as_ptr() as *const f64, n, &mut ptr, &mut m, 1) };
    if code != 0 {
        return Err(crate::Error::Geometry(format!(
            "TetGen failed with code {code}"
        )));
    }
    let mut out = Vec::with_capacity(m as usize);
    if !ptr.is_null() {
        // SAFETY: the shim returned 4m ints at ptr; we copy them and free the array once.
        let raw = unsafe { std::slice::from_raw_parts(ptr, 4 * m as usize) };
        for c in raw.chunks_exact(4) {
            let mut t = [c[0] as u32, c[1] as u32, c[2] as u32, c[3] as u32];
            let p = |i: u32| points[i as usize];
            if pred::orient(p(t[0]), p(t[1]), p(t[2]), p(t[3])) < 0.0 {
                t.swap(0, 1);
            }
            out.push(t);
        }
        unsafe { s2s_tetgen_free(ptr) };
    }
    Ok(out)
}
