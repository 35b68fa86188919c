//! The built-in implementations that `certify` can run by name.

use refrast::{
    ClipMode, Draw, DrawError, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, Resolved,
    SubpixelBits,
};

use crate::restricted::restrictions;

/// Why an implementation cannot be built on this machine: no driver, no such adapter.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unavailable(pub String);

impl std::fmt::Display for Unavailable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// Builds a fresh rasterizer, or says why it cannot here.
pub type Maker = std::sync::Arc<dyn Fn() -> Result<Box<dyn Rasterizer>, Unavailable> + Send + Sync>;

/// Where a built-in comes from, and so what a failure of it means.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Origin {
    /// refrast's own, meant to be correct: `refrast certify` runs these by default.
    Ours,
    /// Someone else's rasterizer behind an adapter: its failures are findings about it.
    ThirdParty,
    /// A course lab's algorithm as the lab describes it.
    Course,
    /// Broken on purpose: the suite must catch it.
    Mutant,
    /// The reference restricted to what a simpler rasterizer supports: it must pass or be
    /// `n/a` on every rule (the suite's own check that it judges any profile).
    Restricted,
}

impl Origin {
    /// As `refrast impls` prints it.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Ours => "ours",
            Self::ThirdParty => "third party",
            Self::Course => "course lab",
            Self::Mutant => "broken on purpose",
            Self::Restricted => "reference, restricted",
        }
    }
}

/// A built-in implementation.
#[derive(Clone)]
pub struct BuiltIn {
    /// The name `--impl` takes.
    pub name: String,
    /// One line on what it is.
    pub description: String,
    /// Where it comes from.
    pub origin: Origin,
    /// Environment variables its process needs (a driver chosen before it loads); `certify`
    /// sets them for each rule's child process.
    pub env: Vec<(String, String)>,
    /// Builds it.
    pub make: Maker,
}

impl BuiltIn {
    /// A built-in that can always be built.
    pub fn new(
        name: impl Into<String>,
        description: impl Into<String>,
        origin: Origin,
        make: impl Fn() -> Box<dyn Rasterizer> + Send + Sync + 'static,
    ) -> Self {
        Self::fallible(name, description, origin, move || Ok(make()))
    }

    /// A built-in that needs something this machine may lack (a driver, a device).
    pub fn fallible(
        name: impl Into<String>,
        description: impl Into<String>,
        origin: Origin,
        make: impl Fn() -> Result<Box<dyn Rasterizer>, Unavailable> + Send + Sync + 'static,
    ) -> Self {
        Self {
            name: name.into(),
            description: description.into(),
            origin,
            env: Vec::new(),
            make: std::sync::Arc::new(make),
        }
    }

    /// The same, with `name=value` set in the environment of the processes it runs in.
    #[must_use]
    pub fn with_env(mut self, name: &str, value: &str) -> Self {
        self.env.push((name.to_owned(), value.to_owned()));
        self
    }

    /// A fresh instance, or why there is none here.
    pub fn build(&self) -> Result<Box<dyn Rasterizer>, Unavailable> {
        (self.make)()
    }
}

impl std::fmt::Debug for BuiltIn {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BuiltIn")
            .field("name", &self.name)
            .field("origin", &self.origin)
            .finish_non_exhaustive()
    }
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

/// Every built-in implementation of this crate: the reference, its configurations, and the
/// reference restricted to each setting ([`crate::restricted`]).
#[must_use]
pub fn builtins() -> Vec<BuiltIn> {
    let mut all = vec![
        BuiltIn::new(
            "reference",
            "the reference: 8 subpixel bits, top-left, guard-band clipping",
            Origin::Ours,
            || Box::new(Reference::default()),
        ),
        BuiltIn::new(
            "reference-full-clip",
            "the reference clipping all six planes (Sutherland–Hodgman, seed 004)",
            Origin::Ours,
            || {
                Box::new(Named::new(
                    "reference-full-clip",
                    ReferenceConfig {
                        clip: ClipMode::Full,
                        ..ReferenceConfig::default()
                    },
                ))
            },
        ),
        BuiltIn::new(
            "reference-4bit",
            "the reference snapping to 4 subpixel bits (Vulkan's minimum)",
            Origin::Ours,
            || {
                Box::new(Named::new(
                    "reference-4bit",
                    ReferenceConfig {
                        subpixel_bits: SubpixelBits::new(4).expect("4 is in range"),
                        ..ReferenceConfig::default()
                    },
                ))
            },
        ),
    ];
    all.extend(restrictions().into_iter().map(|r| {
        let make = r.make;
        BuiltIn::new(
            format!("restricted:{}", r.name),
            format!("the reference restricted: {}", r.description),
            Origin::Restricted,
            move || Box::new(make()),
        )
    }));
    all
}
