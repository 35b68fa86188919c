//! The built-in implementations that `certify` can run by name.

use refrast::{
    ClipMode, Draw, DrawError, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, Resolved,
    SubpixelBits,
};

/// A built-in implementation.
#[derive(Clone, Copy, Debug)]
pub struct BuiltIn {
    /// The name `--impl` takes.
    pub name: &'static str,
    /// One line on what it is.
    pub description: &'static str,
    /// Whether it is meant to be correct (certified by default) or broken on purpose.
    pub correct: bool,
    /// Builds it.
    pub make: fn() -> Box<dyn Rasterizer>,
}

/// The reference under another name and configuration.
#[derive(Clone, Debug)]
pub struct Named {
    name: &'static str,
    inner: Reference,
}

impl Named {
    /// Wraps a configured reference under `name`.
    #[must_use]
    pub fn new(name: &'static str, config: ReferenceConfig) -> Self {
        Self {
            name,
            inner: Reference::new(config),
        }
    }
}

impl Rasterizer for Named {
    fn profile(&self) -> Profile {
        Profile {
            name: self.name.into(),
            ..self.inner.profile()
        }
    }

    fn rasterize(&mut self, draw: &Draw) -> Result<Vec<Fragment>, DrawError> {
        self.inner.rasterize(draw)
    }

    fn resolve(&mut self, draw: &Draw) -> Result<Resolved, DrawError> {
        self.inner.resolve(draw)
    }
}

/// Every built-in implementation.
#[must_use]
pub fn builtins() -> Vec<BuiltIn> {
    vec![
        BuiltIn {
            name: "reference",
            description: "the reference: 8 subpixel bits, top-left, guard-band clipping",
            correct: true,
            make: || Box::new(Reference::default()),
        },
        BuiltIn {
            name: "reference-full-clip",
            description: "the reference clipping all six planes (Sutherland–Hodgman, seed 004)",
            correct: true,
            make: || {
                Box::new(Named::new(
                    "reference-full-clip",
                    ReferenceConfig {
                        clip: ClipMode::Full,
                        ..ReferenceConfig::default()
                    },
                ))
            },
        },
        BuiltIn {
            name: "reference-4bit",
            description: "the reference snapping to 4 subpixel bits (Vulkan's minimum)",
            correct: true,
            make: || {
                Box::new(Named::new(
                    "reference-4bit",
                    ReferenceConfig {
                        subpixel_bits: SubpixelBits::new(4).expect("4 is in range"),
                        ..ReferenceConfig::default()
                    },
                ))
            },
        },
    ]
}

/// The built-in implementation called `name`.
#[must_use]
pub fn builtin(name: &str) -> Option<BuiltIn> {
    builtins().into_iter().find(|b| b.name == name)
}
