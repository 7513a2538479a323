//! Names the renderers' directory for the example and tests that include `tools/render/common`
//! (its scenes directory and assets): `DIFFRACTION_EXAMPLES_ROOT`, `tools/render` beside this
//! package.

fn main() {
    let here = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = std::path::Path::new(&here)
        .parent()
        .expect("gpu-tests lives in the crate's root")
        .join("tools/render");
    println!(
        "cargo:rustc-env=DIFFRACTION_EXAMPLES_ROOT={}",
        root.display()
    );
    println!("cargo:rerun-if-changed=build.rs");
}
