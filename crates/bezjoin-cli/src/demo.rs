//! `bezjoin demo`: the papers' scenarios, run through the same code paths as
//! the subcommands.
//!
//! Every scenario is an ordinary JSON job; the demo writes, per scenario,
//! the picture (`NAME.svg`), the job (`NAME.job.json`, which the matching
//! subcommand accepts as it is) and the result (`NAME.result.json`), then an
//! `index.html` that shows all pictures with captions, and returns the
//! summary table it prints.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

use crate::ops::{self, Scenario};
use crate::svg::escape;
use crate::{CliError, Outcome};

/// One scenario's result.
pub struct Ran {
    /// The scenario.
    pub scenario: Scenario,
    /// What the operation produced.
    pub outcome: Outcome,
}

/// Run every scenario, write the files into `out`, return the summary table.
pub fn run(out: &Path) -> Result<String, CliError> {
    std::fs::create_dir_all(out)
        .map_err(|e| CliError::Io(format!("cannot create {}: {e}", out.display())))?;
    let mut ran = Vec::new();
    for scenario in ops::scenarios() {
        let mut outcome = scenario
            .run()
            .map_err(|e| CliError::Operation(format!("demo scenario {}: {e}", scenario.name)))?;
        outcome.figure.title = scenario.title.to_string();
        write(
            out,
            &format!("{}.svg", scenario.name),
            &outcome.figure.to_svg(),
        )?;
        write(
            out,
            &format!("{}.job.json", scenario.name),
            &pretty(&scenario.job),
        )?;
        write(
            out,
            &format!("{}.result.json", scenario.name),
            &pretty(&outcome.json),
        )?;
        ran.push(Ran { scenario, outcome });
    }
    write(out, "index.html", &index_html(&ran))?;
    let mut table = summary_table(&ran);
    let _ = writeln!(
        table,
        "\nWrote {} pictures and index.html to {}",
        ran.len(),
        out.display()
    );
    Ok(table)
}

fn pretty(value: &Value) -> String {
    let mut s = serde_json::to_string_pretty(value).unwrap_or_default();
    s.push('\n');
    s
}

fn write(dir: &Path, file: &str, text: &str) -> Result<(), CliError> {
    let path = dir.join(file);
    std::fs::write(&path, text)
        .map_err(|e| CliError::Io(format!("cannot write {}: {e}", path.display())))
}

fn number(x: Option<f64>) -> String {
    match x {
        Some(v) => format!("{v:.2e}"),
        None => "-".into(),
    }
}

/// The table the demo prints: scenario, degree, worst continuity residual,
/// max deviation (and what that deviation is measured against).
pub fn summary_table(ran: &[Ran]) -> String {
    let name_width = ran
        .iter()
        .map(|r| r.scenario.name.len())
        .max()
        .unwrap_or(8)
        .max(8);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<name_width$}  {:>6}  {:>26}  {:>13}  deviation measured from",
        "scenario", "degree", "worst continuity residual", "max deviation"
    );
    let _ = writeln!(
        s,
        "{}",
        "-".repeat(name_width + 2 + 6 + 2 + 26 + 2 + 13 + 25)
    );
    for r in ran {
        let sum = &r.outcome.summary;
        let _ = writeln!(
            s,
            "{:<name_width$}  {:>6}  {:>26}  {:>13}  {}",
            r.scenario.name,
            sum.degree,
            number(sum.worst_continuity_jump),
            number(sum.max_deviation),
            if sum.max_deviation.is_some() {
                sum.deviation_meaning
            } else {
                "-"
            }
        );
    }
    let _ = writeln!(
        s,
        "\nworst continuity residual: largest relative jump |left^(j) - right^(j)| / max(|left^(j)|, |right^(j)|, s_j),\n\
         j = 0..k for the promised C^k, measured by the tool from the returned curves at every join (the piece\n\
         before it from the left, the piece after it from the right, also at NURBS knots), in the chain's global\n\
         parameter; s_j = largest |j-th derivative| sampled on the two pieces, so a derivative that vanishes on\n\
         both sides (a line's second) is not a jump (for merges: between P^ and Q^ at R(mu), k = degree).\n\
         For the promised G^k of the fillets by radius: the same for the derivatives with respect to arc\n\
         length (point, unit tangent, curvature vector, ...), s_j sampled on the two pieces."
    );
    s
}

fn index_html(ran: &[Ran]) -> String {
    let mut s = String::new();
    s.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>bezjoin demo</title>\n<style>\n\
         body { font-family: DejaVu Sans, Helvetica, Arial, sans-serif; margin: 2em auto; max-width: 1100px; color: #222; }\n\
         figure { margin: 2em 0; border-top: 1px solid #ddd; padding-top: 1em; }\n\
         figure img { max-width: 100%; }\n\
         figcaption { margin-top: 0.5em; }\n\
         table { border-collapse: collapse; }\n\
         td, th { padding: 2px 10px; border-bottom: 1px solid #eee; text-align: right; }\n\
         td:first-child, th:first-child { text-align: left; }\n\
         code { background: #f4f4f4; padding: 0 3px; }\n\
         </style>\n</head>\n<body>\n<h1>bezjoin demo</h1>\n\
         <p>Each picture shows the given curves (blue), the result (red), changed curves (green) and comparison curves (purple), \
         with control polygons dashed and <b>curvature combs</b>: spikes normal to the curve, of length proportional to the signed curvature, tips joined. \
         One comb scale per picture, so a comb that continues smoothly across a join point shows continuous curvature; a step shows a jump. \
         The fillets by radius show four roundings of one corner side by side (the circular arc in purple, the C<sup>k</sup> fillet in green, the G<sup>2</sup> and G<sup>3</sup> blends in red) \
         with graphs of the curvature along arc length below (dashed lines at the cuts). \
         Every picture has its job next to it (<code>NAME.job.json</code>, accepted as it is by the subcommand named) and its result (<code>NAME.result.json</code>).</p>\n",
    );
    s.push_str("<h2>Summary</h2>\n<table>\n<tr><th>scenario</th><th>subcommand</th><th>degree</th><th>worst continuity residual (C<sup>k</sup> jump)</th><th>max deviation</th><th>deviation measured from</th></tr>\n");
    for r in ran {
        let sum = &r.outcome.summary;
        let _ = writeln!(
            s,
            "<tr><td><a href=\"#{n}\">{n}</a></td><td>{op}</td><td>{d}</td><td>{j}</td><td>{m}</td><td>{w}</td></tr>",
            n = escape(r.scenario.name),
            op = r.scenario.operation.name(),
            d = sum.degree,
            j = number(sum.worst_continuity_jump),
            m = number(sum.max_deviation),
            w = if sum.max_deviation.is_some() {
                escape(sum.deviation_meaning)
            } else {
                "-".into()
            }
        );
    }
    s.push_str("</table>\n");
    for r in ran {
        let n = escape(r.scenario.name);
        let _ = writeln!(
            s,
            "<figure id=\"{n}\">\n<h2>{t}</h2>\n<img src=\"{n}.svg\" alt=\"{t}\">\n<figcaption><p>{d}</p>\n\
             <p>Reproduce: <code>bezjoin {op} {n}.job.json --svg {n}.svg</code> (<a href=\"{n}.job.json\">job</a>, <a href=\"{n}.result.json\">result</a>)</p></figcaption>\n</figure>",
            t = escape(r.scenario.title),
            d = escape(r.scenario.description),
            op = r.scenario.operation.name(),
        );
    }
    s.push_str("</body>\n</html>\n");
    s
}
