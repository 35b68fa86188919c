//! The whole catalogue against the reference clipping x and y at the viewport (`--impl
//! reference-full-clip`): its own code paths (six-plane clipping, a profile without a guard band)
//! are judged by the rules too, not only by unit tests.
fn main() {
    refrast_conformance::run_as_tests(|| {
        refrast::Reference::new(refrast::ReferenceConfig {
            clip: refrast::ClipMode::Full,
            ..refrast::ReferenceConfig::default()
        })
    });
}
