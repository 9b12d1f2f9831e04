//! Links the command line (`[[bin]] dqsym`) as a position-dependent executable on Linux with
//! the GNU toolchain. A position-independent one has every pointer of its read-only data
//! relocated by the dynamic loader at each start (8,726 relocations over 140 kB for the
//! release binary): `dqsym -e 1` spent 110 K of its 1.04 M instructions and 24 page faults on
//! them (callgrind, `perf stat`). The library, the tests and the Python module are not
//! affected (the argument is for this package's binary only).

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && env == "gnu" {
        println!("cargo:rustc-link-arg-bin=dqsym=-no-pie");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
