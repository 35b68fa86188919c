//! Frame times: the rasterizer's share and the whole frame's, kept per frame so that the status
//! line shows a steady recent mean and `--frames` a median over the run.

use std::time::Duration;

/// How many recent frames the status line averages over.
const RECENT: usize = 30;

/// Every frame's time to render (rasterize and shade) and to finish (render, status line, show).
#[derive(Clone, Debug, Default)]
pub struct FrameTimes {
    render: Vec<Duration>,
    frame: Vec<Duration>,
}

/// Median and mean of a run of frame times, in milliseconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// Frames measured.
    pub frames: usize,
    /// The median time, ms.
    pub median_ms: f64,
    /// The mean time, ms.
    pub mean_ms: f64,
}

impl Summary {
    /// Frames per second at the median time.
    #[must_use]
    pub fn fps(&self) -> f64 {
        1000.0 / self.median_ms
    }
}

impl FrameTimes {
    /// Records one frame.
    pub fn push(&mut self, render: Duration, frame: Duration) {
        self.render.push(render);
        self.frame.push(frame);
    }

    /// The mean render and frame times of the last [`RECENT`] frames, ms; zeros before any.
    #[must_use]
    pub fn recent_ms(&self) -> (f64, f64) {
        let mean = |v: &[Duration]| {
            let tail = &v[v.len().saturating_sub(RECENT)..];
            if tail.is_empty() {
                0.0
            } else {
                tail.iter().map(Duration::as_secs_f64).sum::<f64>() * 1000.0 / tail.len() as f64
            }
        };
        (mean(&self.render), mean(&self.frame))
    }

    /// Render and frame summaries, skipping the first `warmup` frames; `None` without frames left.
    #[must_use]
    pub fn summary(&self, warmup: usize) -> Option<(Summary, Summary)> {
        Some((
            summarize(self.render.get(warmup..)?)?,
            summarize(self.frame.get(warmup..)?)?,
        ))
    }
}

fn summarize(times: &[Duration]) -> Option<Summary> {
    if times.is_empty() {
        return None;
    }
    let mut ms: Vec<f64> = times.iter().map(|d| d.as_secs_f64() * 1000.0).collect();
    ms.sort_by(f64::total_cmp);
    let n = ms.len();
    let median_ms = if n % 2 == 1 {
        ms[n / 2]
    } else {
        (ms[n / 2 - 1] + ms[n / 2]) / 2.0
    };
    Some(Summary {
        frames: n,
        median_ms,
        mean_ms: ms.iter().sum::<f64>() / n as f64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(v: u64) -> Duration {
        Duration::from_millis(v)
    }

    #[test]
    fn median_and_mean_after_the_warmup() {
        let mut t = FrameTimes::default();
        for (r, f) in [(100, 200), (4, 8), (2, 5), (3, 6), (9, 10)] {
            t.push(ms(r), ms(f));
        }
        let (render, frame) = t.summary(1).unwrap();
        assert_eq!(render.frames, 4);
        assert!((render.median_ms - 3.5).abs() < 1e-9, "{render:?}");
        assert!((render.mean_ms - 4.5).abs() < 1e-9);
        assert!((frame.median_ms - 7.0).abs() < 1e-9);
        assert!((frame.fps() - 1000.0 / 7.0).abs() < 1e-9);
        assert_eq!(t.summary(5), None);
        assert_eq!(FrameTimes::default().summary(0), None);
    }

    #[test]
    fn the_status_line_averages_recent_frames() {
        let mut t = FrameTimes::default();
        assert_eq!(t.recent_ms(), (0.0, 0.0));
        t.push(ms(1000), ms(1000));
        for _ in 0..RECENT {
            t.push(ms(2), ms(4));
        }
        let (render, frame) = t.recent_ms();
        assert!((render - 2.0).abs() < 1e-9 && (frame - 4.0).abs() < 1e-9);
    }
}
