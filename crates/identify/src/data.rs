//! Measured aggregate quantities: CoR `e` and/or contact duration `t_d` (s) at impact speeds
//! `v_0` (m/s), read from CSV with `#` comment lines; repeated speeds are allowed.

use crate::csv_file::{self, CsvText};
use crate::error::IdentifyError;
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
    /// Half-length of the CoR's error bar at this point, if the data carry a spread: column
    /// `e_std` (a standard deviation, taken as it is) or else `e_spread` (a range, halved).
    /// Drawn in plots, not used by the fit.
    pub spread: Option<f64>,
    /// The standard deviation of this point's CoR as a measurement, if the data give it: column
    /// `e_sem` (the standard error of a mean) or else `e_std` (the scatter of one rebound). The
    /// noise scale of a posterior with given noise.
    pub noise: Option<f64>,
    /// The 1-based line of the file the point was read from (0 for points made in code).
    pub line: u64,
}

/// A dataset: measurements with a common known input.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// Where it came from (for messages).
    pub path: PathBuf,
    /// The measurements, in file order.
    pub points: Vec<Point>,
    /// Admissible but suspicious data, each naming its line (`path:line: ...`).
    pub warnings: Vec<String>,
    /// Whether a comment line calls the data `RECONSTRUCTED`: rebuilt from published results
    /// (e.g. a paper's fitted parameters), not measured.
    pub reconstructed: bool,
    /// The column of the CoR's measurement noise ([`Point::noise`]), if the header has one.
    pub noise_column: Option<&'static str>,
}

impl Dataset {
    /// Reads a CSV file with a header naming `v_0` and at least one of `e`, `t_d` (other
    /// columns are ignored).
    ///
    /// # Errors
    /// [`IdentifyError::Io`] if unreadable, [`IdentifyError::Data`] naming the line and column
    /// of a malformed or inadmissible value, a missing column, or an empty dataset.
    pub fn load(path: &Path) -> Result<Self, IdentifyError> {
        Self::parse(path, &csv_file::read(path)?)
    }

    /// Parses CSV text (`path` is only used in messages).
    ///
    /// # Errors
    /// As [`Dataset::load`].
    pub fn parse(path: &Path, text: &str) -> Result<Self, IdentifyError> {
        let mut csv = CsvText::new(path, text)?;
        let columns =
            Columns::of(&csv.headers).map_err(|message| csv.error(csv.header_line, message))?;
        let headers = csv.headers.clone();
        let mut warnings = Vec::new();
        let points = csv.rows(|record, line| {
            let point = columns.point(&headers, record, line)?;
            if let Some(e) = point.e.filter(|&e| e == 0.0 || e > 1.0) {
                let why = if e == 0.0 {
                    "e = 0 (no rebound): the models give e = 0 only when the bodies never separate"
                        .to_string()
                } else {
                    format!("e = {e} > 1 (energy gained): no model without input reaches it")
                };
                warnings.push(format!("{}:{line}: {why}", path.display()));
            }
            Ok(point)
        })?;
        if points.is_empty() {
            return Err(csv.error(csv.header_line, "the dataset has no data rows".into()));
        }
        if let Some(message) = percent(&points) {
            let line = points.iter().find(|p| p.e.is_some()).map_or(0, |p| p.line);
            return Err(csv.error(line, message));
        }
        warnings.extend(speeds_warning(path, &points));
        warnings.extend(unit_slips(path, &points));
        let reconstructed = text
            .lines()
            .any(|l| l.trim_start().starts_with('#') && l.contains("RECONSTRUCTED"));
        Ok(Self {
            path: path.to_owned(),
            points,
            warnings,
            reconstructed,
            noise_column: columns.noise_name(&headers),
        })
    }

    /// Points at `speeds` (m/s) with nothing measured: where to predict.
    pub fn at_speeds(path: &Path, speeds: &[f64]) -> Self {
        Self {
            path: path.to_owned(),
            points: speeds
                .iter()
                .map(|&v0| Point {
                    v0,
                    e: None,
                    t_d: None,
                    spread: None,
                    noise: None,
                    line: 0,
                })
                .collect(),
            warnings: Vec::new(),
            reconstructed: false,
            noise_column: None,
        }
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

/// What a dataset's header must name.
const NEEDED: &str = "a dataset's header names `v_0` (impact speed, m/s) and `e` (CoR) or `t_d` \
                      (contact duration, s), optionally `e_std`, `e_spread`, `e_sem`";

/// The renames a header seems to need: `v0`, `V_0`, `v_in` for `v_0`; `cor`, `CoR`, `COR`, `CR`,
/// `restitution` for `e`; `td`, `duration` for `t_d` (", rename ..." or empty).
fn renames(names: &[&str]) -> String {
    let key = |h: &str| h.to_lowercase().replace(['_', ' ', '-'], "");
    let wanted = [
        (
            "v_0",
            &["v0", "vin", "v", "speed", "velocity", "impactspeed"][..],
        ),
        (
            "e",
            &[
                "cor",
                "cr",
                "restitution",
                "coefficientofrestitution",
                "epsilon",
            ][..],
        ),
        (
            "t_d",
            &["td", "duration", "contactduration", "tc", "contacttime"][..],
        ),
    ];
    let found: Vec<String> = wanted
        .iter()
        .filter(|(name, _)| !names.contains(name))
        .filter_map(|(name, like)| {
            let h = names.iter().find(|h| like.contains(&key(h).as_str()))?;
            Some(format!("`{h}` to `{name}`"))
        })
        .collect();
    if found.is_empty() {
        String::new()
    } else {
        format!(" (rename {})", found.join(", "))
    }
}

/// The columns of a dataset's header.
struct Columns {
    v0: usize,
    e: Option<usize>,
    t_d: Option<usize>,
    /// The spread's column, and the factor to its half-length (`e_std` 1, `e_spread` 0.5).
    spread: Option<(usize, f64)>,
    /// The noise column (`e_sem`, else `e_std`).
    noise: Option<usize>,
}

impl Columns {
    /// The columns of `headers`; a message for a missing `v_0`, or neither `e` nor `t_d`.
    fn of(headers: &csv::StringRecord) -> Result<Self, String> {
        let col = |name: &str| headers.iter().position(|h| h == name);
        let names: Vec<&str> = headers.iter().collect();
        if names.iter().all(|h| h.is_empty()) {
            return Err(format!("no header: {NEEDED}"));
        }
        let v0 = col("v_0").ok_or_else(|| {
            format!(
                "no column `v_0` in header {names:?}{}: {NEEDED}",
                renames(&names)
            )
        })?;
        let (e, t_d) = (col("e"), col("t_d"));
        if e.is_none() && t_d.is_none() {
            return Err(format!(
                "no column `e` or `t_d` in header {names:?}{}: nothing to fit; {NEEDED}",
                renames(&names)
            ));
        }
        let spread = match (col("e_std"), col("e_spread")) {
            (Some(c), _) => Some((c, 1.0)),
            (None, Some(c)) => Some((c, 0.5)),
            (None, None) => None,
        };
        let noise = col("e_sem").or(col("e_std"));
        Ok(Self {
            v0,
            e,
            t_d,
            spread,
            noise,
        })
    }

    /// The name of the noise column, if there is one.
    fn noise_name(&self, headers: &csv::StringRecord) -> Option<&'static str> {
        let name = headers.get(self.noise?)?;
        ["e_sem", "e_std"].into_iter().find(|n| *n == name)
    }

    /// The measurement of one row; a message for a missing, malformed or inadmissible value.
    fn point(
        &self,
        headers: &csv::StringRecord,
        record: &csv::StringRecord,
        line: u64,
    ) -> Result<Point, String> {
        let field = |c: usize, name: &str| -> Result<f64, String> {
            let raw = record
                .get(c)
                .ok_or_else(|| format!("column `{name}` missing in this row"))?;
            let v: f64 = raw
                .parse()
                .map_err(|_| format!("column `{name}`: {raw:?} is not a number"))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!("column `{name}`: {raw} is not finite"))
            }
        };
        let v0 = field(self.v0, "v_0")?;
        if v0 <= 0.0 {
            return Err(format!(
                "column `v_0`: {v0} is not admissible: v_0 > 0 (m/s)"
            ));
        }
        let e = self.e.map(|c| field(c, "e")).transpose()?;
        if let Some(e) = e.filter(|&e| e < 0.0) {
            return Err(format!("column `e`: {e} is not admissible: e >= 0"));
        }
        let spread = self
            .spread
            .filter(|&(c, _)| record.get(c).is_some_and(|s| !s.is_empty()))
            .map(|(c, factor)| field(c, headers.get(c).unwrap_or("e_std")).map(|x| x * factor))
            .transpose()?;
        let t_d = self.t_d.map(|c| field(c, "t_d")).transpose()?;
        if let Some(t) = t_d.filter(|&t| t <= 0.0) {
            return Err(format!("column `t_d`: {t} is not admissible: t_d > 0 (s)"));
        }
        // Checked where it is used (a posterior with given noise): plots do not need it.
        let noise = self
            .noise
            .and_then(|c| record.get(c))
            .and_then(|raw| raw.parse::<f64>().ok());
        Ok(Point {
            v0,
            e,
            t_d,
            spread,
            noise,
            line,
        })
    }
}

/// A warning where the points cannot pin down a speed dependence: one point, or all at one
/// speed.
/// Impact speeds above this (m/s) get a hint that mm/s may have been meant: the contact
/// experiments these laws are fitted to run at 0.01-60 m/s.
pub const PLAUSIBLE_SPEED: f64 = 100.0;

/// Contact durations above this (s) get a hint that ms may have been meant: the contacts of
/// balls last microseconds to some ten milliseconds.
pub const PLAUSIBLE_DURATION: f64 = 0.5;

/// Hints at unit slips in the columns: speeds in mm/s (above [`PLAUSIBLE_SPEED`]), durations in
/// ms (above [`PLAUSIBLE_DURATION`]). Each names the slip and the fix; the data are used as they
/// are.
fn unit_slips(path: &Path, points: &[Point]) -> Vec<String> {
    let file = path.display();
    let most = |f: &dyn Fn(&Point) -> Option<f64>| points.iter().filter_map(f).reduce(f64::max);
    let mut hints = Vec::new();
    if let Some(v) = most(&|p| Some(p.v0)).filter(|&v| v > PLAUSIBLE_SPEED) {
        hints.push(format!(
            "{file}: v_0 reaches {v}, above the {PLAUSIBLE_SPEED} m/s of any contact experiment: \
             the column looks like a unit slip (mm/s for m/s); divide it by 1000"
        ));
    }
    if let Some(t) = most(&|p| p.t_d).filter(|&t| t > PLAUSIBLE_DURATION) {
        hints.push(format!(
            "{file}: t_d reaches {t} s, longer than the {PLAUSIBLE_DURATION} s of any ball's \
             contact: the column looks like a unit slip (ms for s); divide it by 1000"
        ));
    }
    hints
}

/// The message for a CoR column in percent: every `e` above 1 and none above 100, which no
/// collision without input reaches (a single CoR above 1 among fractions stays a warning).
fn percent(points: &[Point]) -> Option<String> {
    let es = || points.iter().filter_map(|p| p.e);
    let lo = es().reduce(f64::min)?;
    let hi = es().reduce(f64::max)?;
    (lo > 1.0 && hi <= 100.0).then(|| {
        format!(
            "column `e`: all {} CoRs are in ({lo}, {hi}], above 1: these look like percent; \
             divide the column by 100",
            es().count()
        )
    })
}

fn speeds_warning(path: &Path, points: &[Point]) -> Option<String> {
    if points.len() == 1 {
        Some(format!(
            "{}: a single data point: any parameters that fit it are optimal, and no \
             interval can be estimated",
            path.display()
        ))
    } else if points.iter().all(|p| p.v0 == points[0].v0) {
        Some(format!(
            "{}: every point is at v_0 = {} m/s: the data say nothing about other speeds",
            path.display(),
            points[0].v0
        ))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_in_other_units_get_a_hint() {
        let hints = |text: &str| Dataset::parse(Path::new("d.csv"), text).unwrap().warnings;
        // Percent: every e above 1 is an error, said once at the first CoR's line.
        let e = Dataset::parse(Path::new("d.csv"), "# c\nv_0,e\n0.5,91\n1.0,85\n").unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("d.csv:3:"), "{text}");
        assert!(
            text.contains("all 2 CoRs are in (85, 91]")
                && text.contains("divide the column by 100")
        );
        // mm/s.
        let w = hints("v_0,e\n2150,0.6\n3030,0.55\n");
        assert!(w.iter().any(|w| w.contains("mm/s for m/s")), "{w:?}");
        // ms.
        let w = hints("v_0,t_d\n1.0,4.2\n2.0,3.9\n");
        assert!(w.iter().any(|w| w.contains("ms for s")), "{w:?}");
        // Fractions, m/s and seconds: no hint (a CoR of 1.02 is a measurement, not percent).
        assert!(hints("v_0,e,t_d\n0.5,1.02,0.001\n1.0,0.85,0.001\n")
            .iter()
            .all(|w| !w.contains("unit slip")));
    }

    #[test]
    fn a_header_without_the_columns_names_them_and_the_likely_renames() {
        let err = |text: &str| {
            Dataset::parse(Path::new("d.csv"), text)
                .unwrap_err()
                .to_string()
        };
        let e = err("v0,cor\n1,0.5\n");
        assert!(e.starts_with("d.csv:1: no column `v_0`"), "{e}");
        assert!(e.contains("rename `v0` to `v_0`, `cor` to `e`"), "{e}");
        assert!(
            e.contains("names `v_0` (impact speed, m/s) and `e` (CoR) or `t_d`"),
            "{e}"
        );
        let e = err("v_0,CoR\n1,0.5\n");
        assert!(
            e.contains("no column `e` or `t_d`") && e.contains("`CoR` to `e`"),
            "{e}"
        );
        let e = err("");
        assert!(
            e.starts_with("d.csv:1: no header: a dataset's header names"),
            "{e}"
        );
        let e = err("# only a comment\n");
        assert!(e.contains("no header"), "{e}");
    }

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
                t_d: None,
                spread: Some(0.0),
                noise: None,
                line: 5,
            }
        );
        assert!(d.has_cor() && !d.has_durations());
        let d = Dataset::parse(Path::new("d.csv"), "v_0,e,t_d\n0.05,0.38,0.147\n").unwrap();
        assert_eq!(d.points[0].t_d, Some(0.147));
    }

    #[test]
    fn data_rebuilt_from_published_results_say_so() {
        let d = Dataset::parse(Path::new("d.csv"), "# RECONSTRUCTED\nv_0,e\n1,0.9\n").unwrap();
        assert!(d.reconstructed);
        // Only a comment line marks the data; a column named so does not.
        let d = Dataset::parse(Path::new("d.csv"), "v_0,e,RECONSTRUCTED\n1,0.9,0\n").unwrap();
        assert!(!d.reconstructed);
        let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/data");
        assert!(
            Dataset::load(&fixtures.join("kharaz_dss.csv"))
                .unwrap()
                .reconstructed
        );
        let real = fixtures.join("real/baseball_wood_v0_e.csv");
        assert!(!Dataset::load(&real).unwrap().reconstructed);
    }

    #[test]
    fn suspicious_data_are_named_in_warnings() {
        let d = Dataset::parse(Path::new("d.csv"), "v_0,e\n1,1.2\n2,0\n3,0.5\n").unwrap();
        assert_eq!(d.warnings.len(), 2, "{:?}", d.warnings);
        assert!(d.warnings[0].starts_with("d.csv:2:") && d.warnings[0].contains("> 1"));
        assert!(d.warnings[1].starts_with("d.csv:3:") && d.warnings[1].contains("e = 0"));
        let one = Dataset::parse(Path::new("d.csv"), "v_0,e\n1,0.5\n").unwrap();
        assert!(
            one.warnings[0].contains("single data point"),
            "{:?}",
            one.warnings
        );
        let same = Dataset::parse(Path::new("d.csv"), "v_0,e\n1,0.5\n1,0.6\n").unwrap();
        assert!(
            same.warnings[0].contains("every point is at v_0 = 1"),
            "{:?}",
            same.warnings
        );
        let spread = Dataset::parse(Path::new("d.csv"), "v_0,e,e_std\n1,0.5,0.01\n").unwrap();
        assert_eq!(spread.points[0].spread, Some(0.01));
        assert_eq!(spread.points[0].noise, Some(0.01));
        assert_eq!(spread.noise_column, Some("e_std"));
        // A standard error of the mean is the noise of a mean, preferred to the scatter.
        let sem = Dataset::parse(Path::new("d.csv"), "v_0,e,e_std,e_sem\n1,0.5,0.01,0.004\n");
        let sem = sem.unwrap();
        assert_eq!(
            (sem.points[0].noise, sem.noise_column),
            (Some(0.004), Some("e_sem"))
        );
    }

    #[test]
    fn errors_name_the_line() {
        let e = Dataset::parse(Path::new("d.csv"), "# c\nv_0,e\n0.5,0.9\n0.7,abc\n").unwrap_err();
        assert!(
            e.to_string().contains("d.csv:4") && e.to_string().contains("abc"),
            "{e}"
        );
        // Comment and blank lines between the rows count too.
        let text = "# c\nv_0,e\n0.5,0.9\n# mid\n\n0.7,abc\n";
        let e = Dataset::parse(Path::new("d.csv"), text).unwrap_err();
        assert!(e.to_string().contains("d.csv:6"), "{e}");
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
