//! Rows of outside integrators as a CSV file: what `radiometry tradeoff
//! --peers FILE` reads and the Python harness can write, so a report run
//! from the command line shows the peers measured elsewhere (SciPy, vegas,
//! qmcpy, a user's own integrator) beside the built-in integrators.

use super::ExternalRow;
use std::fmt::Write as _;

/// The exact header of a peers file (a contract). `budget` is empty on a
/// to-tolerance row and `tol` on a fixed-budget row; `deterministic` and
/// `resolved` are `true`/`false`.
pub const EXTERNAL_CSV_HEADER: &str = "case,integrator,deterministic,budget,tol,evaluations,estimate,error_estimate,resolved,status_reason,stopped,seconds";

/// The rows as a peers file.
pub fn to_csv(rows: &[ExternalRow]) -> String {
    let mut s = String::from(EXTERNAL_CSV_HEADER);
    s.push('\n');
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{:e},{:e},{},{},{},{:e}",
            r.case,
            r.integrator,
            r.deterministic,
            r.budget.map(|b| b.to_string()).unwrap_or_default(),
            r.tol.map(|t| format!("{t:e}")).unwrap_or_default(),
            r.evaluations,
            r.estimate,
            r.error_estimate,
            r.resolved,
            r.status_reason.replace(',', ";"),
            r.stopped.replace(',', ";"),
            r.seconds
        );
    }
    s
}

/// Parses a peers file; errors name the line and the field.
pub fn from_csv(text: &str) -> Result<Vec<ExternalRow>, String> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == EXTERNAL_CSV_HEADER => {}
        _ => {
            return Err(format!(
                "a peers file starts with the header `{EXTERNAL_CSV_HEADER}`"
            ));
        }
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        if line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        let n = i + 1;
        if f.len() != 12 {
            return Err(format!("line {n}: {} fields, expected 12", f.len()));
        }
        let bool_of = |k: usize, name: &str| match f[k] {
            "true" => Ok(true),
            "false" => Ok(false),
            v => Err(format!("line {n}: {name} `{v}` is not true/false")),
        };
        let num = |k: usize, name: &str| -> Result<f64, String> {
            f[k].parse::<f64>()
                .map_err(|_| format!("line {n}: {name} `{}` is not a number", f[k]))
        };
        let budget = if f[3].is_empty() {
            None
        } else {
            Some(
                f[3].parse::<u32>()
                    .map_err(|_| format!("line {n}: budget `{}` is not a u32", f[3]))?,
            )
        };
        let tol = if f[4].is_empty() {
            None
        } else {
            Some(num(4, "tol")?)
        };
        if budget.is_some() == tol.is_some() {
            return Err(format!("line {n}: exactly one of budget and tol must be given"));
        }
        out.push(ExternalRow {
            case: f[0].to_string(),
            integrator: f[1].to_string(),
            deterministic: bool_of(2, "deterministic")?,
            budget,
            tol,
            evaluations: f[5]
                .parse::<u64>()
                .map_err(|_| format!("line {n}: evaluations `{}` is not a count", f[5]))?,
            estimate: num(6, "estimate")?,
            error_estimate: num(7, "error_estimate")?,
            resolved: bool_of(8, "resolved")?,
            status_reason: f[9].to_string(),
            stopped: f[10].to_string(),
            seconds: num(11, "seconds")?,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peers_files_round_trip_and_reject_bad_rows() {
        let rows = vec![
            ExternalRow {
                case: "ggx-a0.3-to60".into(),
                integrator: "scipy-nquad".into(),
                deterministic: true,
                budget: None,
                tol: Some(8.2e-7),
                evaluations: 3843,
                estimate: 0.8217110031507636,
                error_estimate: 1e-9,
                resolved: true,
                status_reason: String::new(),
                stopped: "tolerance reached".into(),
                seconds: 0.25,
            },
            ExternalRow {
                case: "lambertian-to0".into(),
                integrator: "vegas".into(),
                deterministic: false,
                budget: Some(4096),
                tol: None,
                evaluations: 4000,
                estimate: 1.0,
                error_estimate: 1e-3,
                resolved: false,
                status_reason: "Q < 0.1".into(),
                stopped: String::new(),
                seconds: 0.5,
            },
        ];
        assert_eq!(from_csv(&to_csv(&rows)).unwrap(), rows);
        assert!(from_csv("nope\n").is_err());
        let bad = format!("{EXTERNAL_CSV_HEADER}\nx,y,true,,,1,1,1,true,,,1\n");
        assert!(from_csv(&bad).unwrap_err().contains("exactly one"), "{bad}");
        let bad = format!("{EXTERNAL_CSV_HEADER}\nx,y,maybe,1,,1,1,1,true,,,1\n");
        assert!(from_csv(&bad).unwrap_err().contains("deterministic"));
    }
}
