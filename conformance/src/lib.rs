//! The refrast conformance suite: a catalogue of rules that any [`refrast::Rasterizer`] can be certified against.
#![forbid(unsafe_code)]
