//! Placeholder so that the `lang` branch builds: `lib.rs` on main declares `mod algebra;` but the
//! module lands with the `algebra` branch, whose version replaces this file on merge.
