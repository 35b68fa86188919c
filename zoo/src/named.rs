//! The reference under another name and configuration, for runners and tests that set several
//! side by side.

use refrast::{Draw, DrawError, Fragment, Profile, Rasterizer, Reference, ReferenceConfig, Resolved};

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
