//! TetGen 1.5 as an oracle (cargo feature `tetgen`): Delaunay tetrahedralization of a point set,
//! through our C++ shim `native/tetgen_shim.cpp`. Tetrahedra are returned positively oriented
//! (the kernel's convention, see [`super::pred::orient`]) as indices into the input points.
use super::pred;
use std::os::raw::c_int;
use std::sync::Mutex;

/// TetGen is not reentrant: each run sets process-wide predicate filters from its own bounding
/// box (`exactinit` in `predicates.cxx`), so two runs at once on different boxes decide
/// orientations with each other's error bounds. Every call holds this lock.
static TETGEN: Mutex<()> = Mutex::new(());

extern "C" {
    fn s2s_tetgen_delaunay(
        xyz: *const f64,
        n: c_int,
        tets: *mut *mut c_int,
        ntets: *mut c_int,
        opts: *mut *mut f64,
        nout: *mut c_int,
        quiet: c_int,
    ) -> c_int;
    fn s2s_tetgen_free(p: *mut std::ffi::c_void);
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
    let mut qptr: *mut f64 = std::ptr::null_mut();
    let mut nq: c_int = 0;
    let guard = TETGEN.lock().unwrap_or_else(|p| p.into_inner());
    // SAFETY: the shim reads 3n doubles from a live slice and writes two owned malloc'ed arrays.
    let code = unsafe {
        s2s_tetgen_delaunay(
            points.as_ptr() as *const f64,
            n,
            &mut ptr,
            &mut m,
            &mut qptr,
            &mut nq,
            1,
        )
    };
    drop(guard);
    if code != 0 {
        return Err(crate::Error::Geometry(format!(
            "TetGen failed with code {code}"
        )));
    }
    // Map TetGen's output points back to the first input point at the same position.
    let key = |p: &[f64]| {
        [
            (p[0] + 0.0).to_bits(),
            (p[1] + 0.0).to_bits(),
            (p[2] + 0.0).to_bits(),
        ]
    };
    let mut first = std::collections::HashMap::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        first.entry(key(p)).or_insert(i as u32);
    }
    let mut map = Vec::with_capacity(nq as usize);
    if !qptr.is_null() {
        // SAFETY: the shim returned 3nq doubles at qptr; copied, then freed once.
        let raw = unsafe { std::slice::from_raw_parts(qptr, 3 * nq as usize) };
        for q in raw.chunks_exact(3) {
            map.push(first.get(&key(q)).copied());
        }
        unsafe { s2s_tetgen_free(qptr as *mut _) };
    }
    let mut out = Vec::with_capacity(m as usize);
    let mut unmapped = false;
    if !ptr.is_null() {
        // SAFETY: the shim returned 4m ints at ptr; we copy them and free the array once.
        let raw = unsafe { std::slice::from_raw_parts(ptr, 4 * m as usize) };
        for c in raw.chunks_exact(4) {
            let v = |k: usize| map.get(c[k] as usize).copied().flatten();
            let (Some(a), Some(b), Some(cc), Some(d)) = (v(0), v(1), v(2), v(3)) else {
                unmapped = true;
                continue;
            };
            let mut t = [a, b, cc, d];
            let p = |i: u32| points[i as usize];
            if pred::orient(p(t[0]), p(t[1]), p(t[2]), p(t[3])) < 0.0 {
                t.swap(0, 1);
            }
            out.push(t);
        }
        unsafe { s2s_tetgen_free(ptr as *mut _) };
    }
    if unmapped {
        return Err(crate::Error::Geometry(
            "TetGen returned a point that is not an input point".into(),
        ));
    }
    Ok(out)
}
