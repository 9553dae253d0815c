//! Measured aggregate quantities: CoR `e` and/or contact duration `t_d` (s) at impact speeds
//! `v_0` (m/s), read from CSV with `#` comment lines; repeated speeds are allowed.

use crate::IdentifyError;
use std::path::{Path, PathBuf};

/// One measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Impact speed (m/s), `> 0`.
    pub v0: f64,
    /// Coefficient of restitution, if measured.
    pub e: Option<f64>,
    /// Contact duration (s), if measured.
    pub t_d: Option<f64>,
}

/// A dataset: measurements with a common known input.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// Where it came from (for messages).
    pub path: PathBuf,
    /// The measurements, in file order.
    pub points: Vec<Point>,
}

impl Dataset {
    /// Reads a CSV file with a header naming `v_0` and at least one of `e`, `t_d` (other
    /// columns are ignored).
    ///
    /// # Errors
    /// [`IdentifyError::Io`] if unreadable, [`IdentifyError::Data`] naming the line and column
    /// of a malformed or inadmissible value, a missing column, or an empty dataset.
    pub fn load(path: &Path) -> Result<Self, IdentifyError> {
        let text = std::fs::read_to_string(path).map_err(|source| IdentifyError::Io {
            path: path.to_owned(),
            source,
        })?;
        Self::parse(path, &text)
    }

    /// Parses CSV text (`path` is only used in messages).
    ///
    /// # Errors
    /// As [`Dataset::load`].
    pub fn parse(path: &Path, text: &str) -> Result<Self, IdentifyError> {
        let err = |line: u64, message: String| IdentifyError::Data {
            path: path.to_owned(),
            line,
            message,
        };
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .from_reader(text.as_bytes());
        let header_line = reader.position().line();
        let headers = reader
            .headers()
            .map_err(|e| err(header_line, e.to_string()))?
            .clone();
        let col = |name: &str| headers.iter().position(|h| h == name);
        let header_at = text
            .lines()
            .position(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
            .map_or(1, |i| i as u64 + 1);
        let v0_col = col("v_0").ok_or_else(|| {
            err(
                header_at,
                format!(
                    "no column `v_0` in header {:?}",
                    headers.iter().collect::<Vec<_>>()
                ),
            )
        })?;
        let (e_col, td_col) = (col("e"), col("t_d"));
        if e_col.is_none() && td_col.is_none() {
            return Err(err(
                header_at,
                "no column `e` or `t_d`: nothing to fit".into(),
            ));
        }
        let mut points = Vec::new();
        for record in reader.records() {
            let record =
                record.map_err(|e| err(e.position().map_or(0, |p| p.line()), e.to_string()))?;
            let line = record.position().map_or(0, |p| p.line());
            let field = |c: usize, name: &str| -> Result<f64, IdentifyError> {
                let raw = record
                    .get(c)
                    .ok_or_else(|| err(line, format!("column `{name}` missing in this row")))?;
                let v: f64 = raw
                    .parse()
                    .map_err(|_| err(line, format!("column `{name}`: {raw:?} is not a number")))?;
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(err(line, format!("column `{name}`: {raw} is not finite")))
                }
            };
            let v0 = field(v0_col, "v_0")?;
            if v0 <= 0.0 {
                return Err(err(
                    line,
                    format!("column `v_0`: {v0} is not admissible: v_0 > 0 (m/s)"),
                ));
            }
            let e = e_col.map(|c| field(c, "e")).transpose()?;
            if let Some(e) = e {
                if e < 0.0 {
                    return Err(err(
                        line,
                        format!("column `e`: {e} is not admissible: e >= 0"),
                    ));
                }
            }
            let t_d = td_col.map(|c| field(c, "t_d")).transpose()?;
            if let Some(t) = t_d {
                if t <= 0.0 {
                    return Err(err(
                        line,
                        format!("column `t_d`: {t} is not admissible: t_d > 0 (s)"),
                    ));
                }
            }
            points.push(Point { v0, e, t_d });
        }
        if points.is_empty() {
            return Err(err(header_at, "the dataset has no data rows".into()));
        }
        Ok(Self {
            path: path.to_owned(),
            points,
        })
    }

    /// Whether any point has a measured duration.
    pub fn has_durations(&self) -> bool {
        self.points.iter().any(|p| p.t_d.is_some())
    }

    /// Whether any point has a measured CoR.
    pub fn has_cor(&self) -> bool {
        self.points.iter().any(|p| p.e.is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_comments_repeats_and_optional_columns() {
        let d = Dataset::parse(
            Path::new("d.csv"),
            "# a comment\nv_0,e,e_spread\n0.5,0.9,0.01\n# mid\n0.5,0.91,0.0\n1.0,0.8,0\n",
        )
        .unwrap();
        assert_eq!(d.points.len(), 3);
        assert_eq!(
            d.points[1],
            Point {
                v0: 0.5,
                e: Some(0.91),
                t_d: None
            }
        );
        assert!(d.has_cor() && !d.has_durations());
        let d = Dataset::parse(Path::new("d.csv"), "v_0,e,t_d\n0.05,0.38,0.147\n").unwrap();
        assert_eq!(d.points[0].t_d, Some(0.147));
    }

    #[test]
    fn errors_name_the_line() {
        let e = Dataset::parse(Path::new("d.csv"), "# c\nv_0,e\n0.5,0.9\n0.7,abc\n").unwrap_err();
        assert!(
            e.to_string().contains("d.csv:4") && e.to_string().contains("abc"),
            "{e}"
        );
        let e = Dataset::parse(Path::new("d.csv"), "v_0,e\n-1,0.9\n").unwrap_err();
        assert!(
            e.to_string().contains("d.csv:2") && e.to_string().contains("v_0 > 0"),
            "{e}"
        );
        let e = Dataset::parse(Path::new("d.csv"), "v_0,e\n0.5,NaN\n").unwrap_err();
        assert!(e.to_string().contains("not finite"), "{e}");
        assert!(Dataset::parse(Path::new("d.csv"), "v_0,e\n")
            .unwrap_err()
            .to_string()
            .contains("no data rows"));
        assert!(Dataset::parse(Path::new("d.csv"), "speed,e\n1,2\n")
            .unwrap_err()
            .to_string()
            .contains("v_0"));
        assert!(Dataset::parse(Path::new("d.csv"), "v_0,x\n1,2\n")
            .unwrap_err()
            .to_string()
            .contains("nothing to fit"));
        assert!(Dataset::parse(Path::new("d.csv"), "v_0,e\n1\n").is_err());
    }
}
