//! The zoo: rasterizers that `refrast certify --impl` can run besides the reference.
//!
//! | piece | module | what |
//! |---|---|---|
//! | mutants | [`mutant`] | the reference pipeline with one classic bug each, and the rule family that must catch it |
//! | course rasterizers | [`course`] | the algorithms of the lab documents, implemented as they describe them |
#![forbid(unsafe_code)]

pub mod course;
pub mod mutant;
