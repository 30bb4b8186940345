//! `bezjoin`: smooth joins of Bezier and NURBS curves from the command line.

use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use bezjoin_cli::{CliError, demo, job, ops};
use clap::{Parser, Subcommand};

/// Smooth joins of Bezier and NURBS curves: JSON jobs in, JSON results and SVG pictures
/// (with curvature combs) out.
#[derive(Parser)]
#[command(
    name = "bezjoin",
    version,
    about,
    long_about = None,
    after_help = "Exit codes: 0 success; 1 a file or standard input/output could not be read or written; \
                  2 the job is invalid (not UTF-8, not JSON, or a bad field or value; the message names the field); \
                  3 internal error (a bug: one line on standard error instead of a panic trace)."
)]
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

/// Exit code after an internal error (a panic, which is a bug): distinct from
/// 1 (input/output error) and 2 (bad job).
const EXIT_INTERNAL: i32 = 3;

/// Set to make the tool panic on purpose after parsing its arguments (how
/// the tests check the panic hook).
const PANIC_TEST_VARIABLE: &str = "BEZJOIN_CLI_TEST_PANIC";

fn main() -> ExitCode {
    install_panic_hook();
    let cli = Cli::parse();
    if std::env::var_os(PANIC_TEST_VARIABLE).is_some() {
        panic!("deliberate panic requested by {PANIC_TEST_VARIABLE}");
    }
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

/// Read the job's bytes (a file, or standard input for `-` or nothing);
/// bytes that are not UTF-8 text are a bad job (exit 2), not an I/O error.
fn read_job(path: Option<&Path>) -> Result<(String, String), CliError> {
    let (source, bytes) = match path {
        None => read_stdin()?,
        Some(p) if p == Path::new("-") => read_stdin()?,
        Some(p) => std::fs::read(p)
            .map(|b| (p.display().to_string(), b))
            .map_err(|e| CliError::Io(format!("cannot read {}: {e}", p.display())))?,
    };
    let text = job::decode_text(&source, bytes)?;
    Ok((source, text))
}

fn read_stdin() -> Result<(String, Vec<u8>), CliError> {
    let mut bytes = Vec::new();
    std::io::stdin()
        .read_to_end(&mut bytes)
        .map_err(|e| CliError::Io(format!("cannot read standard input: {e}")))?;
    Ok(("<stdin>".into(), bytes))
}

/// Replace the panic trace by one line on standard error and exit with
/// [`EXIT_INTERNAL`]: a panic is a bug in the tool, not a bad job.
fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<&str>()
            .copied()
            .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
            .unwrap_or("unknown cause");
        let at = info
            .location()
            .map(|l| format!(" ({}:{})", l.file(), l.line()))
            .unwrap_or_default();
        let message = message.lines().collect::<Vec<_>>().join(" ");
        eprintln!("bezjoin: internal error: {message}{at}; this is a bug, please report it");
        std::process::exit(EXIT_INTERNAL);
    }));
}
