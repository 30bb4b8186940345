//! `bezjoin`: smooth joins of Bezier curves from the command line.

use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use bezjoin_cli::{CliError, demo, job, ops};
use clap::{Parser, Subcommand};

/// Smooth joins of Bezier curves: JSON jobs in, JSON results and SVG pictures
/// (with curvature combs) out.
#[derive(Parser)]
#[command(name = "bezjoin", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    #[command(flatten)]
    Operation(ops::Operation),
    /// Reproduce the papers' scenarios: one SVG per scenario, index.html, and a summary table.
    Demo {
        /// Directory to write the pictures and index.html into.
        #[arg(long, value_name = "DIR", default_value = "demo-out")]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo { out } => demo::run(&out).and_then(|table| print_stdout(&table)),
        Command::Operation(op) => run_operation(op),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bezjoin: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run_operation(op: ops::Operation) -> Result<(), CliError> {
    let args = op.args();
    let (source, text) = read_job(args.job.as_deref())?;
    let value = job::parse_text(&source, &text)?;
    let outcome = op.run(&job::Located::root(&value))?;
    if let Some(svg) = &args.svg {
        std::fs::write(svg, outcome.figure.to_svg())
            .map_err(|e| CliError::Io(format!("cannot write {}: {e}", svg.display())))?;
    }
    let text = serde_json::to_string_pretty(&outcome.json)
        .map_err(|e| CliError::Io(format!("cannot format the result: {e}")))?;
    print_stdout(&format!("{text}\n"))
}

/// Write to standard output; a reader that closed the pipe early (`| head`)
/// ends the program normally instead of a panic trace.
fn print_stdout(text: &str) -> Result<(), CliError> {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(CliError::Io(format!("cannot write the result: {e}"))),
    }
}

fn read_job(path: Option<&Path>) -> Result<(String, String), CliError> {
    match path {
        None => read_stdin(),
        Some(p) if p == Path::new("-") => read_stdin(),
        Some(p) => std::fs::read_to_string(p)
            .map(|t| (p.display().to_string(), t))
            .map_err(|e| CliError::Io(format!("cannot read {}: {e}", p.display()))),
    }
}

fn read_stdin() -> Result<(String, String), CliError> {
    let mut text = String::new();
    std::io::stdin()
        .read_to_string(&mut text)
        .map_err(|e| CliError::Io(format!("cannot read standard input: {e}")))?;
    Ok(("<stdin>".into(), text))
}
