//! Helpers shared by the integration tests.
pub mod brute_force;
