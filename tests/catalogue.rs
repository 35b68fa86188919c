//! The whole catalogue against the reference, through the same one line an outside crate uses.

fn main() {
    refrast_conformance::run_as_tests(refrast::Reference::default);
}
