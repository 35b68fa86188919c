//! `DIR/index.html`: the certification as one self-contained page a person can read offline.
//!
//! Pictures are embedded as `data:` URLs and the style is inline, so the page can be mailed or
//! attached to an issue alone. Every string from a report is escaped. The page is written to a
//! temporary file and renamed, so an interrupted run never leaves half a page.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use base64::Engine;
use refrast_conformance::{ProfileReport, Report, Rule, RuleReport, SpecMap, Status};

use super::{Document, Entry, Outcome, Subject, markup_entity, replay_command, reproduce};

/// The page's style: small, inline, no external fonts.
const CSS: &str = include_str!("report.css");

/// Writes into the page how many of its pictures the browser decoded, for a headless check
/// (`scripts/check_report.py`).
const SCRIPT: &str = "addEventListener('load', () => { const all = Array.from(document.images); \
    document.body.dataset.images = all.length; \
    document.body.dataset.imagesDecoded = all.filter((i) => i.complete && i.naturalWidth > 0).length; });";

/// What the page is made from.
pub struct Page<'a> {
    /// The run and what it certified.
    pub doc: &'a Document,
    /// The rules selected, in catalogue order.
    pub rules: &'a [Rule],
}

/// Writes `dir/index.html` through a temporary file renamed into place; returns its path.
pub fn write(dir: &Path, page: &Page<'_>) -> io::Result<PathBuf> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("index.html");
    let temporary = dir.join(format!(".index.html.{}.tmp", std::process::id()));
    std::fs::write(&temporary, render(page)).and_then(|()| std::fs::rename(&temporary, &path))?;
    Ok(path)
}

/// The whole page.
fn render(page: &Page<'_>) -> String {
    let entries = &page.doc.implementations;
    let failed = entries.iter().filter(|e| !e.passed()).count();
    let beyond: usize = entries
        .iter()
        .map(|e| e.report().map_or(0, Report::beyond_spec))
        .sum();
    let beyond = match beyond {
        0 => String::new(),
        n => format!(" ({n} failed beyond the specification claimed)"),
    };
    let verdict = if failed == 0 {
        format!(
            "<p class=\"verdict pass-text\">{} certified, every applicable rule passed{beyond}</p>",
            entries.len()
        )
    } else {
        format!(
            "<p class=\"verdict fail-text\">{failed} of {} failed</p>",
            entries.len()
        )
    };
    let title = if failed == 0 { "passed" } else { "FAILED" };
    let mut h = format!(
        "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>refrast certify: {title}</title>\n<style>\n{CSS}</style>\n</head>\n<body>\n\
         <h1>refrast certify</h1>\n{verdict}\n"
    );
    h.push_str(&summary(page));
    if entries.len() > 1 {
        h.push_str(&matrix(page));
    }
    for (column, entry) in entries.iter().enumerate() {
        h.push_str(&section(page, column, &entry.subject, entry));
    }
    h.push_str(&format!("<script>{SCRIPT}</script>\n</body>\n</html>\n"));
    h
}

/// When, which refrast, where, seed, cases, and the command line.
fn summary(page: &Page<'_>) -> String {
    let run = &page.doc.run;
    let o = &run.options;
    let cases = match (o.cases, &o.proptest_cases) {
        (Some(n), _) => format!("{n} per rule"),
        (None, Some(env)) => format!("PROPTEST_CASES={env}"),
        (None, None) => "each rule's default".to_owned(),
    };
    let scale = if o.scale > 1 {
        format!(", ×{}", o.scale)
    } else {
        String::new()
    };
    let (date, time) = run
        .started
        .trim_end_matches('Z')
        .split_once('T')
        .unwrap_or((&run.started, ""));
    let mut rows = vec![
        ("When", esc(&format!("{date} {time} UTC"))),
        (
            "refrast",
            esc(&format!("{} ({})", run.refrast_version, run.git_revision)),
        ),
        (
            "Host",
            esc(&format!(
                "{} ({} {}, {} processors)",
                run.host.name, run.host.os, run.host.arch, run.host.cpus
            )),
        ),
        ("Seed", o.seed.to_string()),
        ("Cases", format!("{cases}{scale}")),
        ("Rules", format!("{} selected", page.rules.len())),
        (
            "Command",
            format!("<code>{}</code>", esc(&shell_words::join(&run.command))),
        ),
    ];
    if let Some(shard) = o.shard {
        rows.push((
            "Shard",
            format!("{shard} (--shard: this run's part of the rules)"),
        ));
    }
    if !page.doc.not_certified.is_empty() {
        rows.push((
            "Not certified",
            format!("{} (--fail-fast)", esc(&page.doc.not_certified.join(", "))),
        ));
    }
    let rows: String = rows
        .iter()
        .map(|(name, value)| format!("<tr><th>{name}</th><td>{value}</td></tr>\n"))
        .collect();
    format!("<table class=\"summary\">\n{rows}</table>\n")
}

/// Rules as rows, implementations as columns, each cell linking to its detail.
fn matrix(page: &Page<'_>) -> String {
    let mut h = String::from("<h2>Matrix</h2>\n<table class=\"matrix\">\n<tr><th>rule</th>");
    for (column, Entry { subject, .. }) in page.doc.implementations.iter().enumerate() {
        h.push_str(&format!(
            "<th><a href=\"#impl-{column}\">{}</a></th>",
            esc(label(subject))
        ));
    }
    h.push_str("</tr>\n");
    for (row, rule) in page.rules.iter().enumerate() {
        h.push_str(&format!("<tr><th class=\"rule\">{}</th>", esc(rule.id)));
        for (column, entry) in page.doc.implementations.iter().enumerate() {
            let cell = match &entry.outcome {
                Outcome::Certified(report) if report.refused.is_some() => {
                    "<span class=\"status fail\">refused</span>".to_owned()
                }
                Outcome::Certified(report) => match report.rules.iter().find(|r| r.id == rule.id) {
                    Some(r) if explained(r.status) => status_link(r.status, &format!("f{column}-{row}")),
                    Some(r) => status_link(r.status, &format!("r{column}-{row}")),
                    None => "<span class=\"status other\">not run</span>".to_owned(),
                },
                Outcome::Skipped { .. } => "<span class=\"status other\">skipped</span>".to_owned(),
                Outcome::FailedToStart { .. } => "<span class=\"status fail\">no start</span>".to_owned(),
            };
            h.push_str(&format!("<td>{cell}</td>"));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
    h
}

/// A status badge linking to `anchor`.
fn status_link(status: Status, anchor: &str) -> String {
    format!(
        "<a class=\"status {}\" href=\"#{anchor}\">{}</a>",
        class(status),
        status.label()
    )
}

/// The CSS class of a status: a crash, a timeout and a flake are failures, red as a fail.
fn class(status: Status) -> &'static str {
    match status {
        Status::Pass => "pass",
        Status::Fail | Status::Crash | Status::Timeout | Status::Flake => "fail",
        Status::NotApplicable => "na",
        Status::BeyondSpec => "beyond",
    }
}

/// Whether a status gets a section of its own below the table: every failure, and a failure
/// beyond the claimed specification.
fn explained(status: Status) -> bool {
    status.is_failure() || status == Status::BeyondSpec
}

/// How the command line named a subject.
fn label(subject: &Subject) -> &str {
    subject.name()
}

/// One implementation: its profile, its rules' table and its failures.
fn section(page: &Page<'_>, column: usize, subject: &Subject, entry: &Entry) -> String {
    let how = match subject {
        Subject::BuiltIn(_) => "built-in",
        Subject::Exec(_) => "pipe protocol",
    };
    let mut h = format!(
        "<section id=\"impl-{column}\">\n<h2>{} <span class=\"why\">{how}</span></h2>\n",
        esc(label(subject))
    );
    match &entry.outcome {
        Outcome::Skipped { skipped, .. } => {
            h.push_str(&format!(
                "<p><span class=\"status other\">skipped</span> {}</p>\n",
                esc(skipped)
            ));
        }
        Outcome::FailedToStart { failed_to_start, .. } => {
            h.push_str(&format!(
                "<p><span class=\"status fail\">failed to start</span></p>\n<pre>{}</pre>\n",
                esc(failed_to_start)
            ));
        }
        Outcome::Certified(report) if report.refused.is_some() => {
            h.push_str(&format!(
                "<p><span class=\"status fail\">refused</span> {}</p>\n",
                esc(report.refused.as_deref().unwrap_or(""))
            ));
            h.push_str(&profile(&report.profile));
        }
        Outcome::Certified(report) => {
            let (pass, fail, na) = report.tally();
            let beyond = match report.beyond_spec() {
                0 => String::new(),
                n => format!(
                    ", {n} failed beyond what {} requires (<span class=\"status beyond\">BEYOND</span>)",
                    esc(&report.profile.spec)
                ),
            };
            let seconds: f64 = report.rules.iter().map(|r| r.seconds).sum();
            h.push_str(&format!(
                "<p>{pass} passed, {fail} failed{beyond}, {na} not applicable; {seconds:.1} s of rule time</p>\n"
            ));
            h.push_str(&profile(&report.profile));
            h.push_str(&table(page, column, report));
            for (row, rule) in page.rules.iter().enumerate() {
                if let Some(r) = report
                    .rules
                    .iter()
                    .find(|r| r.id == rule.id && explained(r.status))
                {
                    h.push_str(&failure(page, column, row, subject, report, r));
                }
            }
        }
    }
    h.push_str("</section>\n");
    h
}

/// The profile as a definition list.
fn profile(p: &ProfileReport) -> String {
    let features: String = p
        .features
        .iter()
        .map(|f| format!("<span class=\"chip\">{}</span>", esc(f)))
        .collect();
    let mut rows = vec![("profile", esc(&p.name))];
    if !p.about.is_empty() {
        rows.push(("reports itself as", esc(&p.about)));
    }
    rows.extend([
        ("claims", esc(&p.spec)),
        ("snapping", esc(&p.snapping)),
        ("fill", esc(&p.fill)),
        ("depth", esc(&p.depth)),
        (
            "band",
            // A float profile has no grid, so no subpixels: its band is in pixels alone.
            if p.snapping.contains("subpixel") {
                format!("{} px ({} subpixels)", p.band_px, p.tolerance_subpixels)
            } else {
                format!("{} px (no grid)", p.band_px)
            },
        ),
        ("features", features),
    ]);
    let rows: String = rows
        .iter()
        .map(|(k, v)| format!("<dt>{k}</dt><dd>{v}</dd>\n"))
        .collect();
    format!("<dl class=\"profile\">\n{rows}</dl>\n")
}

/// The rules' table of one implementation.
fn table(page: &Page<'_>, column: usize, report: &Report) -> String {
    let mut h = String::from(
        "<table class=\"rules\">\n<tr><th>rule</th><th>family</th><th>kind</th><th>status</th>\
         <th>cases</th><th>seed</th><th>time</th></tr>\n",
    );
    for (row, rule) in page.rules.iter().enumerate() {
        let Some(r) = report.rules.iter().find(|r| r.id == rule.id) else {
            h.push_str(&format!(
                "<tr id=\"r{column}-{row}\"><td class=\"rule\"><code>{}</code></td><td>{}</td><td>{}</td>\
                 <td><span class=\"status other\">not run</span> <span class=\"why\">after a failure \
                 (--fail-fast)</span></td><td></td><td></td><td></td></tr>\n",
                esc(rule.id),
                rule.family.name(),
                rule.kind
            ));
            continue;
        };
        let status = match r.status {
            status if explained(status) => status_link(status, &format!("f{column}-{row}")),
            Status::Pass => format!("<span class=\"status pass\">{}</span>", r.status.label()),
            _ => format!(
                "<span class=\"status na\">n/a</span><span class=\"why\">{}</span>",
                esc(r.message.as_deref().unwrap_or(""))
            ),
        };
        let cases = match (r.status, r.budget_spent) {
            (Status::NotApplicable, _) => String::new(),
            (_, true) => format!("{} of {} (time budget spent)", r.cases, r.planned),
            (_, false) => r.cases.to_string(),
        };
        h.push_str(&format!(
            "<tr id=\"r{column}-{row}\"><td class=\"rule\"><code>{}</code></td><td>{}</td><td>{}</td>\
             <td>{status}</td><td class=\"num\">{cases}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{:.2} s</td></tr>\n",
            esc(&r.id),
            r.family.name(),
            r.kind,
            r.seed,
            r.seconds
        ));
    }
    h.push_str("</table>\n");
    if !report.not_run.is_empty() {
        h.push_str(&format!(
            "<p class=\"note\">--fail-fast: {} rules not run after the first failure.</p>\n",
            report.not_run.len()
        ));
    }
    h
}

/// One failure: message, details, picture, counterexample, and the command that reproduces it.
fn failure(
    page: &Page<'_>,
    column: usize,
    row: usize,
    subject: &Subject,
    report: &Report,
    r: &RuleReport,
) -> String {
    let kind = if r.status == Status::BeyondSpec {
        "failure beyond-spec"
    } else {
        "failure"
    };
    let mut h = format!(
        "<div class=\"{kind}\" id=\"f{column}-{row}\">\n<h3><code>{}</code> on {}</h3>\n\
         <p class=\"message\">{}</p>\n",
        esc(&r.id),
        esc(&report.implementation),
        esc(r.message.as_deref().unwrap_or(""))
    );
    if let Some(note) = &r.spec_note {
        h.push_str(&format!(
            "<p class=\"hint\"><span class=\"status beyond\">beyond the specification</span> {}</p>\n",
            esc(note)
        ));
    }
    if let Some(hint) = &r.hint {
        h.push_str(&format!("<p class=\"hint\"><b>Hint:</b> {}</p>\n", esc(hint)));
    }
    h.push_str(&statements(&r.id));
    if r.details.len() > 1 {
        let details: Vec<String> = r.details.iter().skip(1).map(|d| esc(d)).collect();
        h.push_str(&format!("<h4>Details</h4>\n<pre>{}</pre>\n", details.join("\n")));
    }
    match r.picture.as_deref().map(|p| (p, std::fs::read(p))) {
        Some((_, Ok(png))) => h.push_str(&format!(
            "<h4>Picture</h4>\n<img alt=\"counterexample of {} on {}\" src=\"data:image/png;base64,{}\">\n",
            esc(&r.id),
            esc(&report.implementation),
            base64::engine::general_purpose::STANDARD.encode(png)
        )),
        Some((path, Err(e))) => h.push_str(&format!(
            "<p class=\"note\">The picture {} could not be read: {}</p>\n",
            esc(&path.display().to_string()),
            esc(&e.to_string())
        )),
        None => h.push_str("<p class=\"note\">No picture: this failure draws none.</p>\n"),
    }
    if let Some(case) = &r.case_file {
        h.push_str(&format!(
            "<h4>Counterexample <span class=\"why\">as data: the draw in the pipe protocol's words \
             (docs/json.md)</span></h4>\n<pre><code>{}</code></pre>\n",
            esc(&case.to_json())
        ));
    }
    if let Some(input) = r.counterexample.as_deref().filter(|c| !c.is_empty()) {
        h.push_str(&format!(
            "<h4>Counterexample <span class=\"why\">Rust, after <code>use refrast::*; use \
             refrast_conformance::*;</code></span></h4>\n<pre><code>{}</code></pre>\n",
            esc(input)
        ));
    }
    if let Some(command) = replay_command(subject, r) {
        h.push_str(&format!(
            "<h4>Replay this case alone</h4>\n<pre><code>{}</code></pre>\n",
            esc(&command)
        ));
    }
    h.push_str(&format!(
        "<h4>Reproduce the rule</h4>\n<pre><code>{}</code></pre>\n</div>\n",
        esc(&reproduce(&page.doc.run.options, subject, r))
    ));
    h
}

/// The statements of the specifications that the rule checks, each linked to its section
/// (`docs/spec.md` lists them all); nothing when the spec map names none.
fn statements(rule: &str) -> String {
    static MAP: OnceLock<Option<SpecMap>> = OnceLock::new();
    let Some(map) = MAP.get_or_init(|| refrast_conformance::spec_map().ok()) else {
        return String::new();
    };
    let items: Vec<String> = map
        .statements_for(rule)
        .map(|(spec, s)| {
            let place = format!("{}, {}", spec.title, s.section);
            let place = match spec.link(s) {
                Some(link) => format!("<a href=\"{}\">{}</a>", esc(&link), esc(&place)),
                None => esc(&place),
            };
            format!("<li>{place} <code>{}</code>: {}</li>\n", esc(&s.id), esc(&s.says))
        })
        .collect();
    if items.is_empty() {
        return String::new();
    }
    format!(
        "<h4>What the specifications say <span class=\"why\">(the statements this rule checks)</span></h4>\n<ul class=\"statements\">\n{}</ul>\n",
        items.concat()
    )
}

/// `text` safe inside HTML elements and double-quoted attributes.
fn esc(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match markup_entity(c) {
            Some(entity) => out.push_str(entity),
            None => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::esc;

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            esc("<a href=\"x\">&'</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;"
        );
    }
}
