//! Link options of the command line's binary (`dqsym`); the library is untouched.
//!
//! On GNU/Linux, the binary's relative relocations are packed (`-z pack-relative-relocs`,
//! DT_RELR): a position-independent executable (kept for address randomisation) carries one
//! relocation per pointer in its data, ~8,600 here, which the dynamic loader reads and applies
//! at every start. Packed, their table is 2.4 KB instead of 205 KB, and the loader's
//! relocation time at start fell from ~93,000 to ~55,000 cycles (`LD_DEBUG=statistics`).
//!
//! A loader applies packed relocations only from glibc 2.36 on. The linker marks the binary
//! as needing `GLIBC_ABI_DT_RELR`, so an older loader refuses it with a clear message; but
//! LLD (Rust's default linker here) marks it whether or not the libc linked against has that
//! version, which would make a binary that does not run where it was built. So the option is
//! given only when the C library the binary links against defines `GLIBC_ABI_DT_RELR`, and
//! only for a native build (a cross build's C library is not the one found here).
//!
//! Also on GNU/Linux, natively: the cfg `static_unwinder` when the C compiler has libgcc's
//! static unwinder, `libgcc_eh.a`, which `main.rs` then links into the binary instead of
//! loading `libgcc_s.so.1` at every start (`main.rs` says why).

use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=CC");
    println!("cargo::rustc-check-cfg=cfg(static_unwinder)");
    let var = |name: &str| std::env::var(name).unwrap_or_default();
    let gnu_linux = var("CARGO_CFG_TARGET_OS") == "linux" && var("CARGO_CFG_TARGET_ENV") == "gnu";
    if !gnu_linux || var("TARGET") != var("HOST") {
        return;
    }
    if library("libc.so.6").is_some_and(|path| defines_dt_relr(&path)) {
        println!("cargo:rustc-link-arg-bins=-Wl,-z,pack-relative-relocs");
    }
    if library("libgcc_eh.a").is_some() {
        println!("cargo:rustc-cfg=static_unwinder");
    }
}

/// The path of the library `name` the C compiler links against, if it finds one.
fn library(name: &str) -> Option<String> {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_owned());
    let out = Command::new(cc)
        .arg(format!("-print-file-name={name}"))
        .output()
        .ok()?;
    let path = String::from_utf8_lossy(&out.stdout).trim().to_owned();
    // Without the library, the compiler prints the bare name back.
    (out.status.success() && path.contains('/') && std::path::Path::new(&path).exists())
        .then_some(path)
}

/// Whether the C library at `path` defines the version `GLIBC_ABI_DT_RELR` (glibc 2.36 and
/// later). Any failure to find out is a no.
fn defines_dt_relr(path: &str) -> bool {
    std::fs::read(path).is_ok_and(|bytes| {
        bytes
            .windows(b"GLIBC_ABI_DT_RELR".len())
            .any(|w| w == b"GLIBC_ABI_DT_RELR")
    })
}
