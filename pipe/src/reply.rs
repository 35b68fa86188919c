//! Reading one reply: its header, its binary data and its `end`, each checked against the draw.

use std::time::{Duration, Instant};

use refrast::{Draw, DrawError, Fragment, Resolved};

use super::pipe::{Incoming, Stall};
use super::wire::{self, Declared, MAX_LINE, Op};
use super::{DIED, HANGS};

/// A breach of the protocol, before the exit status and stderr are added.
pub struct Breach(pub String);

/// A reply that kept to the protocol.
pub enum Reply {
    Fragments(Vec<Fragment>),
    Resolved(Resolved),
    /// `error` or `unsupported`: the child refused the draw, as it may.
    Refused(DrawError),
}

/// Reads the reply to `op` on `draw` and checks it against the draw.
pub fn read_reply(
    incoming: &mut Incoming,
    op: Op,
    draw: &Draw,
    declared: &Declared,
    deadline: Instant,
    timeout: Duration,
) -> Result<Reply, Breach> {
    let mut r = Reader {
        incoming,
        draw,
        declared,
        deadline,
        timeout,
    };
    let line = r.incoming.line(deadline, MAX_LINE).map_err(|stall| match stall {
        Stall::TimedOut => r.late("reply"),
        Stall::Closed => Breach(format!("the child's stdout closed before its reply: {DIED}")),
        Stall::LineTooLong => Breach(format!(
            "a reply line longer than {MAX_LINE} bytes where reply belongs"
        )),
    })?;
    let (word, rest) = line.split_once(' ').unwrap_or((line.as_str(), ""));
    let reply = match (op, word) {
        (_, "error") => return Ok(Reply::Refused(DrawError::Backend(rest.to_owned()))),
        (_, "unsupported") => return Ok(Reply::Refused(DrawError::Unsupported(rest.to_owned()))),
        (Op::Rasterize, "fragments") => Reply::Fragments(r.fragments(rest, &line)?),
        (Op::Resolve, "resolved") => Reply::Resolved(r.resolved(rest, &line)?),
        _ => {
            let expected = match op {
                Op::Rasterize => "`fragments COUNT`",
                Op::Resolve => "`resolved WIDTH HEIGHT`",
            };
            return Err(Breach(format!(
                "malformed reply: expected {expected}, `error MESSAGE` or `unsupported MESSAGE` to `{}`, got `{}` \
                 (anything meant for people belongs on stderr)",
                op.word(),
                wire::shown(&line)
            )));
        }
    };
    r.end()?;
    Ok(reply)
}

/// One reply being read: where from, for which draw, by when.
struct Reader<'a> {
    incoming: &'a mut Incoming,
    draw: &'a Draw,
    declared: &'a Declared,
    deadline: Instant,
    timeout: Duration,
}

impl Reader<'_> {
    /// The breach of a child that sent no `what` in time.
    fn late(&self, what: &str) -> Breach {
        Breach(format!(
            "no {what} within {} s: {HANGS} (or is far too slow; the per-draw timeout is \
             --case-timeout)",
            self.timeout.as_secs_f64()
        ))
    }

    /// How the messages name the draw's primitives: "2 triangles", "3 line-strip primitives".
    fn primitives(&self) -> String {
        let n = self.draw.primitive_count();
        if self.draw.topology == refrast::Topology::TriangleList {
            format!("{n} triangles")
        } else if self.draw.topology.is_triangles() {
            format!("{n} {} triangles", self.draw.topology)
        } else {
            format!("{n} {} primitives", self.draw.topology)
        }
    }

    /// `n` bytes of binary data, `what` they are for the messages; `counted` when the reply's
    /// own count says how many (a late end may then be a wrong count).
    fn bytes(&mut self, n: usize, what: &str, counted: bool) -> Result<Vec<u8>, Breach> {
        let deadline = self.deadline;
        self.incoming.bytes(n, deadline).map_err(|(stall, got)| {
            let what = format!("{what} ({n} bytes; {got} came)");
            match stall {
                Stall::Closed => Breach(format!(
                    "truncated reply: the child's stdout closed within {what}"
                )),
                _ if counted => self.late(&format!("end of {what} (is the count right?)")),
                _ => self.late(&format!("end of {what}")),
            }
        })
    }

    /// The records after `fragments COUNT` (`rest` is the count), each inside the draw.
    fn fragments(&mut self, rest: &str, line: &str) -> Result<Vec<Fragment>, Breach> {
        let (width, height) = (self.draw.viewport.width(), self.draw.viewport.height());
        let (triangles, samples) = (self.draw.primitive_count(), self.draw.samples);
        let most = u64::from(width) * u64::from(height) * triangles as u64 * u64::from(samples);
        let count: u64 = rest.trim().parse().map_err(|_| {
            Breach(format!(
                "malformed reply `{}`: the count is not a number",
                wire::shown(line)
            ))
        })?;
        if count > most {
            return Err(Breach(format!(
                "wrong count: {count} fragments, more than the {width}×{height} viewport times {} \
                 times {samples} samples allows ({most})",
                self.primitives()
            )));
        }
        let count = count as usize;
        let record = wire::fragment_bytes(self.declared.version);
        let bytes = self.bytes(count * record, &format!("{count} fragments"), true)?;
        let screen = self.declared.profile.features.screen_barycentrics;
        let mut fragments = Vec::with_capacity(count);
        for (k, record) in bytes.chunks_exact(record).enumerate() {
            let f = wire::fragment(record, screen, samples)
                .map_err(|why| Breach(format!("fragment {k} of {count}: {why}")))?;
            if f.x >= width || f.y >= height {
                return Err(Breach(format!(
                    "fragment {k} of {count} lies at ({}, {}), outside the {width}×{height} viewport",
                    f.x, f.y
                )));
            }
            if f.primitive as usize >= triangles {
                return Err(Breach(format!(
                    "fragment {k} of {count} names primitive {}, but the draw has {}",
                    f.primitive,
                    self.primitives()
                )));
            }
            fragments.push(f);
        }
        Ok(fragments)
    }

    /// The buffers after `resolved WIDTH HEIGHT` (`rest` is the size), one value per sample,
    /// sample-minor: pixel (x, y)'s samples together.
    fn resolved(&mut self, rest: &str, line: &str) -> Result<Resolved, Breach> {
        let draw = self.draw;
        let (width, height, samples) = (draw.viewport.width(), draw.viewport.height(), draw.samples);
        let size: Vec<Option<u32>> = rest.split_whitespace().map(|w| w.parse().ok()).collect();
        if size != [Some(width), Some(height)] {
            return Err(Breach(format!(
                "wrong count: the reply `{}` should be `resolved {width} {height}`, the draw's viewport",
                wire::shown(line)
            )));
        }
        let cells = draw.viewport.pixel_count() * usize::from(samples);
        let what = format!("the {width}×{height}×{samples} depth and primitive buffers");
        let bytes = self.bytes(cells * 8, &what, false)?;
        let primitive = wire::primitives(&bytes[cells * 4..]);
        let triangles = draw.primitive_count();
        if let Some((i, p)) = primitive
            .iter()
            .enumerate()
            .find_map(|(i, p)| p.filter(|&p| p as usize >= triangles).map(|p| (i, p)))
        {
            let pixel = i / usize::from(samples);
            return Err(Breach(format!(
                "pixel ({}, {}) of the primitive buffer names primitive {p}, but the draw has {} \
                 (0xFFFFFFFF means none)",
                pixel % width as usize,
                pixel / width as usize,
                self.primitives()
            )));
        }
        Ok(Resolved {
            viewport: draw.viewport,
            samples,
            depth: wire::floats(&bytes[..cells * 4]),
            primitive,
        })
    }

    /// The `end` line after the reply's data.
    fn end(&mut self) -> Result<(), Breach> {
        let end = self.incoming.line(self.deadline, MAX_LINE).map_err(|s| match s {
            Stall::Closed => Breach("truncated reply: the child's stdout closed before `end`".into()),
            Stall::TimedOut => self.late("`end` after the reply"),
            Stall::LineTooLong => {
                Breach("wrong count: binary data goes on where `end` belongs (is the count right?)".into())
            }
        })?;
        if end != "end" {
            return Err(Breach(format!(
                "wrong count: expected `end` after the reply's data, got `{}` (is the count right?)",
                wire::shown(&end)
            )));
        }
        Ok(())
    }
}
