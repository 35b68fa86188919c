//! The zoo: rasterizers that `refrast certify --impl` can run besides the reference. Each
//! depends on the contract alone (`refrast`); the suite that judges them is only their tests'.
//!
//! | piece | module | what |
//! |---|---|---|
//! | mutants | [`mutant`] | the reference pipeline with one classic bug each, and the rule family that must catch it |
//! | course rasterizers | [`course`] | the algorithms of the lab documents, implemented as they describe them |
//! | the reference renamed | [`named`] | [`Named`]: the reference under another name and configuration |
//! | the reference restricted | [`restricted`] | declaring and using one setting or a few: every rule must still ask its question |
//! | the reference shaped | [`shaped`] | shaped like the rasterizers that exposed false verdicts: a GPU, a 2D scan converter |
#![forbid(unsafe_code)]

pub mod course;
pub mod mutant;
pub mod named;
pub mod restricted;
pub mod shaped;

pub use named::Named;
