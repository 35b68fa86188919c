//! The whole conformance catalogue against `fast`, through the same one line an outside crate uses.

fn main() {
    refrast_conformance::run_as_tests(refrast_fast::Fast::default);
}
