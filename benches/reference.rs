//! Benchmarks of the reference (filled in below).
fn main() {}
