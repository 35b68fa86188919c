//! What a failed check returns: a message, sample counts, and a picture of the samples.

use std::fmt;

use refrast::{DrawError, Fragment};

use crate::status::Status;
use refrast_pipe::Misbehaviour;

/// How one sample came out against what was expected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Class {
    /// Not covered, and rightly so.
    Empty,
    /// Covered once, and rightly so.
    Covered,
    /// Should be covered, is not (purple).
    Missing,
    /// Covered, should not be (red).
    Unexpected,
    /// Covered more than once (blue).
    Double,
    /// Within the tolerance band of an edge: either answer is right (yellow).
    DontCare,
}

/// What a sample should get.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Expect {
    /// No fragment.
    Zero,
    /// Exactly one fragment.
    One,
    /// Not judged: the sample is in the tolerance band of a boundary or a cut, where snapping
    /// may move that edge over it, even over a neighbour's sample (then it counts twice).
    ZeroOrOne,
    /// Covered, once or twice: inside the mesh, within the band of an edge that ends at a
    /// vertex made by clipping. Both triangles sharing it cut it alike, so no hole may open,
    /// but the snapped cut vertex can push them both over a third triangle's sample.
    OneOrTwo,
}

/// The tally of a coverage comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct Counts {
    /// Samples that should be covered and are not.
    pub missing: usize,
    /// Samples covered that should not be.
    pub unexpected: usize,
    /// Samples covered more than once.
    pub double: usize,
    /// Samples in the tolerance band (not judged).
    pub dont_care: usize,
}

/// A picture of a viewport's samples with the triangles drawn over them (data: the runner that
/// wants a file saves it with [`crate::RuleReport::save_exhibit`]; it travels from a rule's
/// child process).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Picture {
    /// Viewport width in pixels.
    pub width: u32,
    /// Viewport height in pixels.
    pub height: u32,
    /// One class per pixel, row-major.
    pub classes: Vec<Class>,
    /// Closed outlines in raster space (pixels), usually one per triangle.
    pub outlines: Vec<Vec<[f64; 2]>>,
}

/// Why a check failed.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// What went wrong, in one or a few sentences.
    pub message: String,
    /// Sample tallies, for coverage checks (boxed, as the picture: a violation travels in
    /// every `Err`).
    pub counts: Option<Box<Counts>>,
    /// The samples, for coverage checks (boxed: a violation travels in every `Err`).
    pub picture: Option<Box<Picture>>,
    /// Every sample the failure is about (drawn red when there is no picture).
    pub samples: Vec<(u32, u32)>,
    /// The numbers behind the failure, one line per wrong sample (the first few).
    pub details: Vec<String>,
    /// What the failure makes of the rule: [`Status::Fail`] for a wrong answer,
    /// [`Status::Crash`] or [`Status::Timeout`] when there was no answer to judge.
    pub status: Status,
}

impl Violation {
    /// A violation with only a message.
    #[must_use]
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            counts: None,
            picture: None,
            samples: Vec::new(),
            details: Vec::new(),
            status: Status::Fail,
        }
    }

    /// The violation of a draw that returned `error` (`what` names the call): a crash or a hang
    /// of a child behind a pipe ([`Misbehaviour`]) is a `crash` or a `timeout`.
    #[must_use]
    pub fn of_draw_error(what: &str, error: &DrawError) -> Self {
        let status = match error {
            DrawError::Misbehaved(message) => match Misbehaviour::of(message) {
                Misbehaviour::Hung => Status::Timeout,
                Misbehaviour::Died => Status::Crash,
                Misbehaviour::Garbled => Status::Fail,
            },
            _ => Status::Fail,
        };
        Self {
            status,
            ..Self::new(format!("{what} returned an error: {error}"))
        }
    }

    /// The violation of a rasterizer that panicked with `what`.
    #[must_use]
    pub fn panicked(what: &str) -> Self {
        Self {
            status: Status::Crash,
            ..Self::new(format!("the rasterizer panicked: {what}"))
        }
    }

    /// The violation with `context` before its message: what the draw was, so that a crash or
    /// an error says what it happened on.
    #[must_use]
    pub fn on(self, context: &str) -> Self {
        Self {
            message: format!("{context}: {}", self.message),
            ..self
        }
    }

    /// A violation about one sample, pixel `(x, y)`.
    #[must_use]
    pub fn at(sample: (u32, u32), message: impl Into<String>) -> Self {
        Self {
            samples: vec![sample],
            ..Self::new(message)
        }
    }
}

/// `n` and a noun, singular or plural: `1 fragment`, `3 fragments`.
#[must_use]
pub fn plural(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// What one check finds wrong, sample by sample: every wrong sample is pictured, the first few
/// described with their numbers.
#[derive(Clone, Debug, Default)]
pub struct Findings {
    samples: Vec<(u32, u32)>,
    details: Vec<String>,
}

impl Findings {
    /// How many wrong samples are described with their numbers.
    pub const DESCRIBED: usize = 8;

    /// Nothing found yet.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Records a wrong sample; `detail` says what is wrong there, with the numbers.
    pub fn add(&mut self, sample: (u32, u32), detail: impl FnOnce() -> String) {
        if self.details.len() < Self::DESCRIBED {
            self.details.push(detail());
        }
        self.samples.push(sample);
    }

    /// Whether nothing was found.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }

    /// `Ok` when nothing was found, else a violation whose message is `summary(n)` for `n` wrong
    /// samples followed by the first one's numbers.
    pub fn verdict(self, summary: impl FnOnce(usize) -> String) -> Result<(), Violation> {
        if self.is_empty() {
            return Ok(());
        }
        let mut message = summary(self.samples.len());
        if let Some(first) = self.details.first() {
            message.push_str(": ");
            message.push_str(first);
        }
        Err(Violation {
            samples: self.samples,
            details: self.details,
            ..Violation::new(message)
        })
    }
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)?;
        if let Some(c) = &self.counts {
            write!(
                f,
                " ({} missing, {} unexpected, {} double-covered, {} don't care)",
                c.missing, c.unexpected, c.double, c.dont_care
            )?;
        }
        Ok(())
    }
}

/// Fragments per pixel, row-major.
#[must_use]
pub fn count_fragments(fragments: &[Fragment], width: u32, height: u32) -> Vec<u32> {
    let mut counts = vec![0; width as usize * height as usize];
    for f in fragments.iter().filter(|f| f.x < width && f.y < height) {
        counts[f.y as usize * width as usize + f.x as usize] += 1;
    }
    counts
}

/// Compares per-sample counts with expectations; on a mismatch the violation carries counts and
/// a picture. `what` names the expectation for the message.
pub fn compare_coverage(
    counts: &[u32],
    expected: &[Expect],
    width: u32,
    height: u32,
    outlines: Vec<Vec<[f64; 2]>>,
    what: &str,
) -> Result<(), Violation> {
    let mut tally = Counts::default();
    let classes: Vec<Class> = counts
        .iter()
        .zip(expected)
        .map(|(&n, &e)| {
            let class = match (e, n) {
                (Expect::ZeroOrOne, _) => Class::DontCare,
                (Expect::OneOrTwo, 1 | 2) => Class::Covered,
                (Expect::OneOrTwo, 0) => Class::Missing,
                (_, 2..) => Class::Double,
                (Expect::One, 1) => Class::Covered,
                (Expect::One, _) => Class::Missing,
                (Expect::Zero, 0) => Class::Empty,
                (Expect::Zero, _) => Class::Unexpected,
            };
            match class {
                Class::Missing => tally.missing += 1,
                Class::Unexpected => tally.unexpected += 1,
                Class::Double => tally.double += 1,
                Class::DontCare => tally.dont_care += 1,
                Class::Empty | Class::Covered => {}
            }
            class
        })
        .collect();
    if tally.missing + tally.unexpected + tally.double == 0 {
        return Ok(());
    }
    Err(Violation {
        message: format!("coverage differs from {what}"),
        counts: Some(Box::new(tally)),
        samples: Vec::new(),
        details: Vec::new(),
        status: Status::Fail,
        picture: Some(Box::new(Picture {
            width,
            height,
            classes,
            outlines,
        })),
    })
}
