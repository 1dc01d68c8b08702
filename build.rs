// Builds the TetGen oracle shim only with the `tetgen` feature, so the default build needs no C++ library.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=native");
    #[cfg(feature = "tetgen")]
    tetgen::build();
}

#[cfg(feature = "tetgen")]
mod tetgen {
    pub fn build() {
        cc::Build::new()
            .cpp(true)
            .file("native/tetgen_shim.cpp")
            .flag_if_supported("-std=c++11")
            .flag_if_supported("-w")
            .compile("tetgen_shim");
        println!("cargo:rustc-link-lib=tet");
        println!("cargo:rustc-link-lib=stdc++");
    }
}
