//! What a rule's run came to: pass, a failure of one kind or another, or no verdict to give.

use serde::{Deserialize, Serialize};

/// A rule's outcome.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Status {
    /// Every case held.
    #[serde(rename = "pass")]
    Pass,
    /// A case failed.
    #[serde(rename = "fail")]
    Fail,
    /// The rule does not apply to the profile.
    #[serde(rename = "n/a")]
    NotApplicable,
    /// A case failed, on something the specification the profile claims does not require
    /// ([`crate::RuleReport::spec_note`] says why): not a failure of conformance, and not a pass.
    #[serde(rename = "beyond-spec")]
    BeyondSpec,
    /// The rasterizer panicked, or its process died, on a case: no answer to judge.
    #[serde(rename = "crash")]
    Crash,
    /// The rasterizer did not answer a case within the case timeout (`--case-timeout`).
    #[serde(rename = "timeout")]
    Timeout,
    /// A case failed, and the shrunk counterexample passed when replayed: a nondeterministic
    /// answer, which no specification allows (the same draw must give the same fragments).
    #[serde(rename = "flake")]
    Flake,
}

impl Status {
    /// Every status, in the order reports list them.
    pub const ALL: [Self; 7] = [
        Self::Pass,
        Self::Fail,
        Self::Crash,
        Self::Timeout,
        Self::Flake,
        Self::BeyondSpec,
        Self::NotApplicable,
    ];

    /// As printed: `pass`, `FAIL`, `CRASH`, `TIMEOUT`, `FLAKE`, `n/a`, `BEYOND` (beyond the
    /// claimed specification).
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::Fail => "FAIL",
            Self::NotApplicable => "n/a",
            Self::BeyondSpec => "BEYOND",
            Self::Crash => "CRASH",
            Self::Timeout => "TIMEOUT",
            Self::Flake => "FLAKE",
        }
    }

    /// The word JSON, expectation files and JUnit use: `pass`, `fail`, `n/a`, `beyond-spec`,
    /// `crash`, `timeout`, `flake`.
    #[must_use]
    pub fn word(self) -> &'static str {
        match self {
            Self::Pass => "pass",
            Self::Fail => "fail",
            Self::NotApplicable => "n/a",
            Self::BeyondSpec => "beyond-spec",
            Self::Crash => "crash",
            Self::Timeout => "timeout",
            Self::Flake => "flake",
        }
    }

    /// The status a [`Status::word`] names.
    #[must_use]
    pub fn from_word(word: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.word() == word)
    }

    /// Whether the rule failed the implementation: `fail`, `crash`, `timeout` and `flake` do
    /// (and make `certify` exit 1 without expectations); `pass`, `n/a` and `beyond-spec` do not.
    #[must_use]
    pub fn is_failure(self) -> bool {
        matches!(self, Self::Fail | Self::Crash | Self::Timeout | Self::Flake)
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.word())
    }
}
