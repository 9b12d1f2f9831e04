//! The command line's link: on Linux with glibc, a position-dependent executable.
//!
//! A position-independent one (the default) is relocated by the loader at every start: the
//! binary's 8,600 relative relocations write into its 39 pages of read-only-after-relocation
//! data (tables of string slices, vtables, clap's command tree), so each page they touch is
//! copied on its first write. Linked at a fixed address, the linker resolves them once and the
//! pages are read from the file as they are needed: `dqsym -e 1` 967 k -> 856 k instructions
//! (callgrind) and 278 -> 258 page faults (`perf record -e page-faults`, 2-4 us each on a
//! virtual machine). The cost is that the binary's own code and data are not at a random
//! address (the libraries, the stack and the heap still are). Only the binary: the library,
//! its tests and the Python module are linked as before.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && env == "gnu" {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}
