//! `usar trust`: RNE trust values between robots and groups (paper Defs. 1-3, Eqs. 7-17).

use std::io::Write;

use anyhow::{Context, Result, bail};
use clap::Args;
use rne_core::{
    Alignment, DEFAULT_RELATIVE_EPSILON, Distribution, LogBase, NeedsMatrix, NeedsVector,
    RneOptions, Smoothing, TrustModel, Weights,
};

use usar_report::table::{column_width, matrix, row_minima, sig6};

const EXAMPLES: &str = "\
Examples:
  # Paper Example 1: T(R1||R2) = 0.00372546, T(R1||R3) = 0.000504443 nats
  usar trust --weights 6,4,2 --needs 86,120,30 --needs 20,30,10 --needs 80,115,25

  # Paper Examples 2-3: robot-group and group-group trust
  usar trust --weights 6,4,2 --needs 86,120,30 --group \"82,114,24;79,117,23\" --group \"40,56,12;56,48,15\"

  # Base-10 logarithm, no smoothing, sorted distributions (Algorithm 4)
  usar trust --weights 1,1 --needs 1,3 --needs 3,1 --log-base 10 --epsilon 0 --sorted

Output: each needs distribution, then T(row || column) matrices; lower RNE = more trust,
'*' marks the lowest value of each row (excluding the diagonal).";

/// Arguments of `usar trust`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct TrustArgs {
    /// Weight of each needs category, comma-separated (j values, each > 0).
    #[arg(long, value_name = "W1,W2,..", allow_hyphen_values = true)]
    pub weights: String,

    /// A robot's needs vector, comma-separated (j values, each >= 0). Repeat for each robot
    /// (R1, R2, ...).
    #[arg(long = "needs", value_name = "N1,N2,..", allow_hyphen_values = true)]
    pub needs: Vec<String>,

    /// A group's needs matrix: robots separated by ';', needs by ','. Repeat for each group
    /// (G1, G2, ...). Adds robot-group and group-group trust.
    #[arg(long = "group", value_name = "ROW;ROW;..", allow_hyphen_values = true)]
    pub groups: Vec<String>,

    /// Logarithm base: e (nats), 2 (bits), 10 or any number > 1.
    #[arg(long, value_name = "BASE", default_value = "e")]
    pub log_base: String,

    /// Sort each distribution before comparing (Algorithm 4) instead of aligning categories.
    #[arg(long)]
    pub sorted: bool,

    /// Relative smoothing: add EPS x total weighted needs to each weighted need before
    /// normalising; 0 disables it (RNE may then be inf).
    #[arg(long, value_name = "EPS", default_value_t = DEFAULT_RELATIVE_EPSILON, allow_hyphen_values = true)]
    pub epsilon: f64,
}

/// Parses a comma-separated list of numbers; `what` names the input in errors.
fn parse_list(text: &str, what: &str) -> Result<Vec<f64>> {
    text.split(',')
        .map(|t| {
            let t = t.trim();
            t.parse::<f64>()
                .with_context(|| format!("{what}: {t:?} is not a number"))
        })
        .collect()
}

/// Parses one `--needs` or a group row and checks its length against the weights.
fn parse_needs(text: &str, what: &str, j: usize) -> Result<NeedsVector> {
    let values = parse_list(text, what)?;
    if values.len() != j {
        bail!("{what} has {} values but --weights has {j}", values.len());
    }
    NeedsVector::new(values).with_context(|| what.to_string())
}

fn unit(base: LogBase) -> String {
    match base.value() {
        _ if base == LogBase::E => "nats (natural log)".into(),
        2.0 => "bits (log base 2)".into(),
        10.0 => "hartleys (log base 10)".into(),
        _ => format!("log base {base} units"),
    }
}

fn distribution_lines(labels: &[String], dists: &[Distribution]) -> String {
    let w = column_width(labels.iter().map(String::len).max().unwrap_or(0));
    labels
        .iter()
        .zip(dists)
        .map(|(l, d)| {
            let v: Vec<String> = d
                .as_slice()
                .iter()
                .map(|x| format!("{:>10}", sig6(*x)))
                .collect();
            format!("  {l:w$}  {}\n", v.join(" "))
        })
        .collect()
}

/// One side of an RNE matrix: labels and their distributions.
struct Side<'a> {
    labels: &'a [String],
    dists: &'a [Distribution],
}

/// The parsed input of `usar trust`: the trust model (weights and RNE options), each robot's
/// needs vector (R1, R2, ...) and each group's needs matrix (G1, G2, ...).
struct TrustInput {
    model: TrustModel,
    robots: Vec<NeedsVector>,
    groups: Vec<NeedsMatrix>,
}

/// The needs distributions of the robots and of the groups, with their labels (`R1`.., `G1`..).
struct Distributions {
    robot_labels: Vec<String>,
    robots: Vec<Distribution>,
    group_labels: Vec<String>,
    groups: Vec<Distribution>,
}

/// Runs `usar trust`, writing the report to `out`.
///
/// # Errors
/// A one-line message for bad input (naming the flag and its 1-based occurrence), or an I/O
/// error.
pub fn run(args: &TrustArgs, out: &mut dyn Write) -> Result<()> {
    let input = parse_input(args)?;
    let dists = distributions(&input)?;
    write_report(args, &input.model, &dists, out)
}

/// Parses the flags into the trust model, the robots' needs vectors and the groups' needs
/// matrices, checking in flag order: `--weights`, at least one robot or group, each
/// `--needs`, each `--group`, `--log-base`, then `--epsilon`.
fn parse_input(args: &TrustArgs) -> Result<TrustInput> {
    let weights = Weights::new(parse_list(&args.weights, "--weights")?).context("--weights")?;
    let j = weights.len();
    if args.needs.is_empty() && args.groups.is_empty() {
        bail!("give at least one --needs or --group");
    }
    let robots = args
        .needs
        .iter()
        .enumerate()
        .map(|(i, t)| parse_needs(t, &format!("--needs #{}", i + 1), j))
        .collect::<Result<Vec<_>>>()?;
    let groups = args
        .groups
        .iter()
        .enumerate()
        .map(|(g, t)| parse_group(t, g, j))
        .collect::<Result<Vec<_>>>()?;
    let model = trust_model(args, weights)?;
    Ok(TrustInput {
        model,
        robots,
        groups,
    })
}

/// Parses the `--group` number `g` (0-based) into a group's needs matrix: robots separated by
/// `;`, each a needs vector of `j` values.
fn parse_group(text: &str, g: usize, j: usize) -> Result<NeedsMatrix> {
    let rows = text
        .split(';')
        .enumerate()
        .map(|(r, row)| parse_needs(row, &format!("--group #{} row {}", g + 1, r + 1), j))
        .collect::<Result<Vec<_>>>()?;
    NeedsMatrix::from_members(&rows).with_context(|| format!("--group #{}", g + 1))
}

/// The trust model of `weights` and the RNE options of `--log-base`, `--epsilon` (0 = no
/// smoothing) and `--sorted`.
fn trust_model(args: &TrustArgs, weights: Weights) -> Result<TrustModel> {
    let log_base: LogBase = args.log_base.parse().context("--log-base")?;
    let smoothing = if args.epsilon == 0.0 {
        Smoothing::None
    } else {
        Smoothing::Relative(args.epsilon)
    };
    let alignment = if args.sorted {
        Alignment::Sorted
    } else {
        Alignment::Category
    };
    TrustModel::new(
        weights,
        RneOptions {
            smoothing,
            alignment,
            log_base,
        },
    )
    .context("--epsilon")
}

/// The needs distribution of each robot (Eq. 8) and each group (Eq. 11), labelled `R1`..
/// and `G1`..; errors name the `--needs` or `--group` they come from.
fn distributions(input: &TrustInput) -> Result<Distributions> {
    let model = &input.model;
    let robot_labels: Vec<String> = (1..=input.robots.len()).map(|i| format!("R{i}")).collect();
    let group_labels: Vec<String> = (1..=input.groups.len()).map(|i| format!("G{i}")).collect();
    let robots = (input.robots.iter().enumerate())
        .map(|(i, r)| {
            model
                .distribution(r)
                .with_context(|| format!("--needs #{}", i + 1))
        })
        .collect::<Result<Vec<_>>>()?;
    let groups = (input.groups.iter().enumerate())
        .map(|(g, m)| {
            model
                .group_distribution(m)
                .with_context(|| format!("--group #{}", g + 1))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Distributions {
        robot_labels,
        robots,
        group_labels,
        groups,
    })
}

/// Writes the report to `out`: the header (weights, alignment, smoothing, unit), the needs
/// distributions, then the robot-robot, robot-group and group-group RNE matrices (each
/// skipped when a side is empty).
fn write_report(
    args: &TrustArgs,
    model: &TrustModel,
    dists: &Distributions,
    out: &mut dyn Write,
) -> Result<()> {
    write_header(&args.weights, model.options(), out)?;
    writeln!(out, "\nNeeds distributions (Eqs. 8, 11):")?;
    write!(
        out,
        "{}",
        distribution_lines(&dists.robot_labels, &dists.robots)
    )?;
    write!(
        out,
        "{}",
        distribution_lines(&dists.group_labels, &dists.groups)
    )?;
    let robots_side = Side {
        labels: &dists.robot_labels,
        dists: &dists.robots,
    };
    let groups_side = Side {
        labels: &dists.group_labels,
        dists: &dists.groups,
    };
    let sections = [
        (
            "Robot-robot RNE T(Ri || Rj) (Eq. 7):",
            &robots_side,
            &robots_side,
            true,
        ),
        (
            "Robot-group RNE T(Ri || Gk) (Eq. 12):",
            &robots_side,
            &groups_side,
            false,
        ),
        (
            "Group-group RNE T(Gk || Gl) (Eq. 17):",
            &groups_side,
            &groups_side,
            true,
        ),
    ];
    for (title, trustors, trustees, square) in sections {
        write_rne_section(model, title, trustors, trustees, square, out)?;
    }
    Ok(())
}

/// Writes the report's first two lines: the weights as given (`weights`, the flag's text), the
/// alignment and smoothing, and the unit of the RNE values (all three from `options`).
fn write_header(weights: &str, options: &RneOptions, out: &mut dyn Write) -> Result<()> {
    let smoothing_text = match options.smoothing {
        Smoothing::Relative(e) => format!("relative smoothing {e:e}"),
        _ => "no smoothing".to_string(),
    };
    let align_text = match options.alignment {
        Alignment::Sorted => "sorted (Algorithm 4)",
        Alignment::Category => "category-aligned",
    };
    writeln!(out, "Weights: {weights}; {align_text}; {smoothing_text}")?;
    writeln!(
        out,
        "RNE T(row || column) in {}; lower = more trust; * = lowest in row",
        unit(options.log_base)
    )?;
    Ok(())
}

/// Writes one RNE matrix `T(trustor || trustee)` under `title`, '*' marking each row's
/// lowest value (excluding the diagonal when `square`); writes nothing when either side is
/// empty.
fn write_rne_section(
    model: &TrustModel,
    title: &str,
    trustors: &Side<'_>,
    trustees: &Side<'_>,
    square: bool,
    out: &mut dyn Write,
) -> Result<()> {
    if trustors.dists.is_empty() || trustees.dists.is_empty() {
        return Ok(());
    }
    let values = rne_matrix(model, trustors.dists, trustees.dists)?;
    let minima: Vec<Vec<usize>> = values
        .iter()
        .enumerate()
        .map(|(r, row)| row_minima(row, square.then_some(r)))
        .collect();
    writeln!(out, "\n{title}")?;
    write!(
        out,
        "{}",
        matrix(trustors.labels, trustees.labels, &values, |r, c| minima[r]
            .contains(&c))
    )?;
    Ok(())
}

/// The RNE `T(p || q)` of each row distribution `p` (trustor) against each column
/// distribution `q` (trustee), row by row.
fn rne_matrix(
    model: &TrustModel,
    rows: &[Distribution],
    cols: &[Distribution],
) -> Result<Vec<Vec<f64>>> {
    rows.iter()
        .map(|p| cols.iter().map(|q| Ok(model.rne(p, q)?)).collect())
        .collect()
}
