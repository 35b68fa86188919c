//! The guard band: how far outside the viewport a triangle may reach before x/y clipping moves
//! its edges.
//!
//! The sample (11.5, 7.5) of a 16×16 target lies exactly on an edge leaving the viewport on the
//! right, towards a vertex [`REACHES`] pixels beyond it (42 slopes in 1/8 px, the third vertex on
//! either side: 84 triangles per reach, all on the 1/8-px grid, in one draw). A driver that does not clip
//! them covers the sample as its tie rule says; one that clips at the viewport snaps each cut
//! vertex, which moves the edge off the sample for most slopes and may flip it. The same edges
//! ending inside the viewport are the control: they must follow the tie rule.

use refrast::{ClipMode, DrawError, FillConvention, Rasterizer, Reference, ReferenceConfig};

use super::{Raster, batch, clip, covers};

/// The reaches tried, in pixels beyond the viewport's right side; the last is the reference's
/// own guard band ([`refrast::GUARD_BAND_REACH`]).
pub const REACHES: [u32; 7] = [2, 8, 32, 128, 512, 2048, refrast::GUARD_BAND_REACH];

/// What the guard-band probe saw.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// Per reach, how many tie samples were covered against the tie rule, of how many.
    pub flips: Vec<(u32, usize, usize)>,
    /// The same against the control, whose edges end inside.
    pub control: (usize, usize),
    /// Whether there was a tie rule to measure by.
    pub measured: bool,
}

impl Band {
    /// The largest reach tried with no flip at it or below; 0 when the first flips, when the
    /// control fails, or without a tie rule.
    #[must_use]
    pub fn reach(&self) -> u32 {
        if !self.measured || self.control.0 > 0 {
            return 0;
        }
        self.flips
            .iter()
            .take_while(|(_, flips, _)| *flips == 0)
            .last()
            .map_or(0, |(reach, _, _)| *reach)
    }

    /// What was seen, as a report says it.
    #[must_use]
    pub fn describe(&self) -> String {
        if !self.measured {
            return "no guard band (no tie rule to see edges move by)".to_owned();
        }
        if self.control.0 > 0 {
            return format!(
                "no guard band ({}/{} tie samples on edges ending inside break the tie rule)",
                self.control.0, self.control.1
            );
        }
        let first = self.flips.iter().find(|(_, flips, _)| *flips > 0);
        match (self.reach(), first) {
            (0, Some((reach, flips, tried))) => format!(
                "no guard band ({flips}/{tried} tie samples flip once the edge reaches {reach} px outside)"
            ),
            (reach, Some((beyond, flips, tried))) => format!(
                "a {reach}-px guard band (no tie sample flips up to {reach} px outside; {flips}/{tried} at {beyond} px)"
            ),
            (reach, None) => {
                format!("a {reach}-px guard band (no tie sample flips up to {reach} px outside)")
            }
        }
    }
}

/// Draws the leaving edges of every reach in one draw, the control in another.
pub fn probe(draw: &mut Raster<'_>, fill: Option<FillConvention>) -> Result<Band, DrawError> {
    let Some(fill) = fill else {
        return Ok(Band {
            flips: Vec::new(),
            control: (0, 0),
            measured: false,
        });
    };
    let e = 0.125;
    let s = [11.5, 7.5];
    let (mut leaving, mut inside) = (Vec::new(), Vec::new());
    for reach in REACHES.into_iter().map(f64::from) {
        for p in [3.0f64, 5.0, 7.0, 9.0, 11.0, 13.0] {
            for q in [-7.0f64, -5.0, -3.0, -1.0, 1.0, 3.0, 5.0, 7.0]
                .into_iter()
                .filter(|q| q.abs() <= p)
            {
                for side in [1.0, -1.0] {
                    let along = |m: f64| [s[0] + m * p * e, s[1] + m * q * e];
                    let a = along(-(24.0 / p).ceil());
                    // The far vertex: the last grid point of the line within `reach` of x = 16.
                    let b = along(((16.0 + reach - s[0]) / (p * e)).floor());
                    let c = [s[0] - side * 3.0 * q * e, s[1] + side * 3.0 * p * e];
                    leaving.extend([a, b, c]);
                    if reach == f64::from(REACHES[0]) {
                        inside.extend([a, along((4.0 / (p * e)).floor()), c]);
                    }
                }
            }
        }
    }
    // Per triangle, whether the driver and the reference under `fill` disagree on the sample.
    let mut wrong = |points: &[[f64; 2]]| -> Result<Vec<bool>, DrawError> {
        let d = batch(
            16,
            16,
            points.iter().map(|&p| clip(16, 16, p, 0.5, 1.0)).collect(),
        );
        let n = points.len() / 3;
        let got = covers(&draw(&d)?, n, (11, 7));
        let mut reference = Reference::new(ReferenceConfig {
            fill,
            clip: ClipMode::GuardBand,
            ..ReferenceConfig::default()
        });
        let want = covers(&reference.rasterize(&d)?, n, (11, 7));
        Ok(got.iter().zip(&want).map(|(g, w)| g != w).collect())
    };
    let control = wrong(&inside)?;
    let leaving = wrong(&leaving)?;
    let flips = REACHES
        .into_iter()
        .zip(leaving.chunks(control.len()))
        .map(|(reach, w)| (reach, w.iter().filter(|&&w| w).count(), w.len()))
        .collect();
    let control = (control.iter().filter(|&&w| w).count(), control.len());
    Ok(Band {
        flips,
        control,
        measured: true,
    })
}
