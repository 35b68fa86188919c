//! The SIMD levels `fast` can draw at, named, so that a configuration, a test or a benchmark can
//! ask for one and a report can say which ran.

use fearless_simd::Level;

/// A SIMD level of the back end.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SimdLevel {
    /// The best the CPU has, detected at run time.
    #[default]
    Best,
    /// No SIMD: scalar code (on x86-64 and AArch64, whose baselines have SIMD, only with the
    /// default feature `force_support_fallback`).
    Fallback,
    /// x86 SSE2, the x86-64 baseline.
    Sse2,
    /// x86-64-v2: SSE4.2.
    Sse4_2,
    /// x86-64-v3: AVX2 and FMA (which `fast` does not use).
    Avx2,
    /// Ice Lake-class AVX-512.
    Avx512,
    /// AArch64 NEON.
    Neon,
}

impl SimdLevel {
    /// Every named level, from none to the widest.
    pub const ALL: [Self; 6] = [
        Self::Fallback,
        Self::Sse2,
        Self::Sse4_2,
        Self::Avx2,
        Self::Avx512,
        Self::Neon,
    ];

    /// Its name, as reports and `--simd`-style options write it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Best => "best",
            Self::Fallback => "fallback",
            Self::Sse2 => "sse2",
            Self::Sse4_2 => "sse4.2",
            Self::Avx2 => "avx2",
            Self::Avx512 => "avx512",
            Self::Neon => "neon",
        }
    }

    /// The fearless_simd level, or `None` when this CPU (or this build) does not have it.
    #[must_use]
    pub fn level(self) -> Option<Level> {
        let best = Level::new();
        match self {
            Self::Best => Some(best),
            Self::Fallback => fallback(),
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Self::Sse2 => best.as_sse2().map(Level::Sse2),
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Self::Sse4_2 => best.as_sse4_2().map(Level::Sse4_2),
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Self::Avx2 => best.as_avx2().map(Level::Avx2),
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Self::Avx512 => best.as_avx512().map(Level::Avx512),
            #[cfg(target_arch = "aarch64")]
            Self::Neon => best.as_neon().map(Level::Neon),
            #[allow(unreachable_patterns, reason = "which levels exist depends on the target")]
            _ => None,
        }
    }

    /// The named level `level` is.
    #[must_use]
    pub fn of(level: Level) -> Self {
        match level {
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Level::Avx512(_) => Self::Avx512,
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Level::Avx2(_) => Self::Avx2,
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Level::Sse4_2(_) => Self::Sse4_2,
            #[cfg(any(target_arch = "x86", target_arch = "x86_64"))]
            Level::Sse2(_) => Self::Sse2,
            #[cfg(target_arch = "aarch64")]
            Level::Neon(_) => Self::Neon,
            #[allow(unreachable_patterns, reason = "which levels exist depends on the target")]
            _ => Self::Fallback,
        }
    }
}

/// The scalar fallback, where this build supports it.
fn fallback() -> Option<Level> {
    #[cfg(feature = "force_support_fallback")]
    return Some(Level::fallback());
    #[cfg(not(feature = "force_support_fallback"))]
    {
        let baseline = Level::baseline();
        baseline.is_fallback().then_some(baseline)
    }
}
