//! Every rasterizer refrast can run by name: what `refrast certify --impl`, `refrast impls` and
//! the `builtin` fuzz target choose from.
//!
//! The implementations know nothing of it: each depends on `refrast` alone, and this crate
//! lists them, so adding one rebuilds only this crate and its users.
//!
//! | what | where |
//! |---|---|
//! | an entry | [`BuiltIn`], [`Origin`], [`Maker`] |
//! | the list | [`all`], [`find`] |
#![forbid(unsafe_code)]

mod entries;

use std::sync::Arc;

use refrast::{Rasterizer, Unavailable};

pub use entries::all;

/// Builds a fresh rasterizer, or says why it cannot here.
pub type Maker = Arc<dyn Fn() -> Result<Box<dyn Rasterizer>, Unavailable> + Send + Sync>;

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
    /// The reference shaped like a rasterizer unlike it (a GPU, a 2D scan converter), correct:
    /// it must pass, be `n/a` or be beyond its claimed specification on every rule.
    Shaped,
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
            Self::Shaped => "reference, shaped",
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
            make: Arc::new(make),
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

/// The built-in called `name`, or a message that lists every name.
pub fn find(name: &str) -> Result<BuiltIn, String> {
    let mut all = all();
    match all.iter().position(|b| b.name == name) {
        Some(i) => Ok(all.swap_remove(i)),
        None => {
            let names: Vec<_> = all.iter().map(|b| b.name.as_str()).collect();
            Err(format!(
                "no implementation named '{name}'; the built-ins are: {}",
                names.join(", ")
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let all = all();
        let mut names: Vec<&str> = all.iter().map(|b| b.name.as_str()).collect();
        names.sort_unstable();
        let before = names.len();
        names.dedup();
        assert_eq!(names.len(), before, "two built-ins share a name");
    }

    #[test]
    fn every_origin_is_listed_and_ours_come_first() {
        let all = all();
        for origin in [
            Origin::Ours,
            Origin::Course,
            Origin::Mutant,
            Origin::Restricted,
            Origin::Shaped,
        ] {
            assert!(all.iter().any(|b| b.origin == origin), "no {origin:?} built-in");
        }
        #[cfg(feature = "third-party")]
        for name in ["euc", "lavapipe", "llvmpipe", "softpipe", "swiftshader", "vulkan"] {
            let b = find(name).expect("listed");
            assert_eq!(b.origin, Origin::ThirdParty, "{name}");
        }
        assert_eq!(all[0].name, "reference");
    }

    #[test]
    fn the_always_buildable_build_here() {
        for b in all().iter().filter(|b| b.origin != Origin::ThirdParty) {
            let r = b
                .build()
                .unwrap_or_else(|why| panic!("{} cannot be built: {why}", b.name));
            let profile = r.profile();
            assert!(!profile.name.is_empty(), "{} names its profile", b.name);
        }
    }

    #[test]
    fn an_unknown_name_lists_the_known_ones() {
        let err = find("no-such-rasterizer").expect_err("not a built-in");
        assert!(
            err.contains("no-such-rasterizer") && err.contains("reference") && err.contains("fast"),
            "{err}"
        );
    }

    #[test]
    fn a_driver_carries_the_environment_it_needs() {
        #[cfg(feature = "third-party")]
        {
            let softpipe = find("softpipe").expect("listed");
            assert!(
                softpipe
                    .env
                    .iter()
                    .any(|(k, v)| k == "GALLIUM_DRIVER" && v == "softpipe")
            );
        }
        assert!(find("reference").expect("listed").env.is_empty());
    }
}
