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
    let late = |what: &str| {
        Breach(format!(
            "no {what} within {} s: {HANGS} (or is far too slow; the per-draw timeout is \
             --case-timeout)",
            timeout.as_secs_f64()
        ))
    };
    let stalled = |stall: Stall, what: &str| match stall {
        Stall::TimedOut => late(what),
        Stall::Closed => Breach(format!("the child's stdout closed before its {what}: {DIED}")),
        Stall::LineTooLong => Breach(format!(
            "a reply line longer than {MAX_LINE} bytes where {what} belongs"
        )),
    };
    let line = incoming
        .line(deadline, MAX_LINE)
        .map_err(|s| stalled(s, "reply"))?;
    let (word, rest) = line.split_once(' ').unwrap_or((line.as_str(), ""));
    let (width, height) = (draw.viewport.width(), draw.viewport.height());
    let triangles = draw.primitive_count();
    let samples = draw.samples;
    // How the messages name the draw's primitives: "2 triangles", "3 line-strip primitives".
    let unit = if draw.topology == refrast::Topology::TriangleList {
        "triangles".to_owned()
    } else {
        format!("{} primitives", draw.topology)
    };
    let reply = match (op, word) {
        (_, "error") => return Ok(Reply::Refused(DrawError::Backend(rest.to_owned()))),
        (_, "unsupported") => return Ok(Reply::Refused(DrawError::Unsupported(rest.to_owned()))),
        (Op::Rasterize, "fragments") => {
            let most = u64::from(width) * u64::from(height) * triangles as u64 * u64::from(samples);
            let count: u64 = rest.trim().parse().map_err(|_| {
                Breach(format!(
                    "malformed reply `{}`: the count is not a number",
                    wire::shown(&line)
                ))
            })?;
            if count > most {
                return Err(Breach(format!(
                    "wrong count: {count} fragments, more than the {width}×{height} viewport times {triangles} \
                     {unit} times {samples} samples allows ({most})"
                )));
            }
            let count = count as usize;
            let record = wire::fragment_bytes(declared.version);
            let bytes = incoming.bytes(count * record, deadline).map_err(|(stall, got)| {
                let what = format!("{count} fragments ({} bytes; {got} came)", count * record);
                match stall {
                    Stall::Closed => Breach(format!(
                        "truncated reply: the child's stdout closed within {what}"
                    )),
                    _ => late(&format!("end of {what} (is the count right?)")),
                }
            })?;
            let mut fragments = Vec::with_capacity(count);
            for (k, record) in bytes.chunks_exact(record).enumerate() {
                let f = wire::fragment(record, declared.profile.features.screen_barycentrics, samples)
                    .map_err(|why| Breach(format!("fragment {k} of {count}: {why}")))?;
                if f.x >= width || f.y >= height {
                    return Err(Breach(format!(
                        "fragment {k} of {count} lies at ({}, {}), outside the {width}×{height} viewport",
                        f.x, f.y
                    )));
                }
                if f.primitive as usize >= triangles {
                    return Err(Breach(format!(
                        "fragment {k} of {count} names primitive {}, but the draw has {triangles} {unit}",
                        f.primitive
                    )));
                }
                fragments.push(f);
            }
            Reply::Fragments(fragments)
        }
        (Op::Resolve, "resolved") => {
            let size: Vec<Option<u32>> = rest.split_whitespace().map(|w| w.parse().ok()).collect();
            if size != [Some(width), Some(height)] {
                return Err(Breach(format!(
                    "wrong count: the reply `{}` should be `resolved {width} {height}`, the draw's viewport",
                    wire::shown(&line)
                )));
            }
            // One value per sample, sample-minor: pixel (x, y)'s samples together.
            let pixels = draw.viewport.pixel_count() * usize::from(samples);
            let bytes = incoming.bytes(pixels * 8, deadline).map_err(|(stall, got)| {
                let what = format!(
                    "the {width}×{height}×{samples} depth and primitive buffers ({} bytes; {got} came)",
                    pixels * 8
                );
                match stall {
                    Stall::Closed => Breach(format!(
                        "truncated reply: the child's stdout closed within {what}"
                    )),
                    _ => late(&format!("end of {what}")),
                }
            })?;
            let primitive = wire::primitives(&bytes[pixels * 4..]);
            if let Some((i, p)) = primitive
                .iter()
                .enumerate()
                .find_map(|(i, p)| p.filter(|&p| p as usize >= triangles).map(|p| (i, p)))
            {
                return Err(Breach(format!(
                    "pixel ({}, {}) of the primitive buffer names primitive {p}, but the draw has {triangles} \
                     {unit} (0xFFFFFFFF means none)",
                    (i / usize::from(samples)) % width as usize,
                    (i / usize::from(samples)) / width as usize
                )));
            }
            Reply::Resolved(Resolved {
                viewport: draw.viewport,
                samples,
                depth: wire::floats(&bytes[..pixels * 4]),
                primitive,
            })
        }
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
    let end = incoming.line(deadline, MAX_LINE).map_err(|s| match s {
        Stall::Closed => Breach("truncated reply: the child's stdout closed before `end`".into()),
        Stall::TimedOut => late("`end` after the reply"),
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
    Ok(reply)
}
