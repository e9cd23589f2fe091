//! Motions read from a table: a CSV file of times and values, interpolated by natural
//! cubic splines, whose first and second derivatives are continuous, so that the walls'
//! velocity and acceleration have no jumps between the table's rows.
//!
//! Written here rather than taken from a crate: the spline is forty lines, and the
//! crates that offer a C² spline with its derivatives pull a linear-algebra stack
//! (ndarray-linalg) into the build.

use crate::error::{Result, SphError};
use std::path::Path;

/// The natural cubic spline through `(t_k, y_k)`: `S'' = 0` at both ends. With
/// `h = t_(k+1) - t_k`, `a = (t_(k+1) - t)/h`, `b = 1 - a` and the knots' second
/// derivatives `M_k` (a tridiagonal solve),
/// `S = a y_k + b y_(k+1) + [(a³ - a) M_k + (b³ - b) M_(k+1)] h²/6`.
#[derive(Debug, Clone)]
pub struct Spline {
    t: Vec<f64>,
    y: Vec<f64>,
    m: Vec<f64>,
}

impl Spline {
    /// The spline through `t` (strictly increasing, at least two) and `y`.
    pub fn new(t: Vec<f64>, y: Vec<f64>) -> Self {
        let n = t.len();
        let mut m = vec![0.0; n];
        if n > 2 {
            // Thomas algorithm on h_(k-1) M_(k-1) + 2(h_(k-1) + h_k) M_k + h_k M_(k+1) = r_k
            let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
            let slope: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
            let (mut diag, mut rhs) = (vec![0.0; n], vec![0.0; n]);
            for k in 1..n - 1 {
                diag[k] = 2.0 * (h[k - 1] + h[k]);
                rhs[k] = 6.0 * (slope[k] - slope[k - 1]);
                if k > 1 {
                    let w = h[k - 1] / diag[k - 1];
                    diag[k] -= w * h[k - 1];
                    rhs[k] -= w * rhs[k - 1];
                }
            }
            for k in (1..n - 1).rev() {
                m[k] = (rhs[k] - h[k] * m[k + 1]) / diag[k];
            }
        }
        Self { t, y, m }
    }

    /// `(S, S', S'')` at `x`, held at the end values (zero slope) outside the table
    /// (which covers the run).
    pub fn at(&self, x: f64) -> [f64; 3] {
        let n = self.t.len();
        if x < self.t[0] {
            return [self.y[0], 0.0, 0.0];
        }
        if x > self.t[n - 1] {
            return [self.y[n - 1], 0.0, 0.0];
        }
        let k = self.t.partition_point(|&t| t <= x).clamp(1, n - 1) - 1;
        let h = self.t[k + 1] - self.t[k];
        let a = (self.t[k + 1] - x) / h;
        let b = 1.0 - a;
        let (y0, y1, m0, m1) = (self.y[k], self.y[k + 1], self.m[k], self.m[k + 1]);
        [
            a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0,
            (y1 - y0) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0,
            a * m0 + b * m1,
        ]
    }
}

/// The columns of a motion table's CSV file: rows are lines of numbers separated by
/// commas or spaces; `#` starts a comment, and a first line that is not numbers is a
/// header. Refused in one line naming `key`: a file that cannot be read, a line that is
/// not numbers, and what [`columns`] refuses.
pub fn read_columns(key: &str, path: &Path, end: f64) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let shown = format!("{:?}", path.display().to_string());
    let refuse = |expected: String| Err(SphError::invalid(key, &shown, expected));
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) => return refuse(format!("a readable CSV file ({e})")),
    };
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for (line_no, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let words = line.split([',', ' ', '\t']).filter(|w| !w.is_empty());
        let numbers: Option<Vec<f64>> = words.map(|w| w.parse::<f64>().ok()).collect();
        match numbers {
            None if rows.is_empty() => continue,
            Some(row) => rows.push(row),
            None => return refuse(format!("rows of numbers (line {}: {line:?})", line_no + 1)),
        }
    }
    columns(key, &shown, &rows, end)
}

/// The columns of a motion table's `rows` (shown as `shown` in messages): times and,
/// per value column, its values. Refused in one line naming `key`: rows of unequal
/// width, a value that is not a finite number, times that do not increase, fewer than
/// two rows, or a table that does not cover `[0, end]`.
pub fn columns(
    key: &str,
    shown: &str,
    rows: &[Vec<f64>],
    end: f64,
) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    let refuse = |expected: String| Err(SphError::invalid(key, shown, expected));
    let width = rows.first().map_or(0, Vec::len);
    if let Some(k) =
        (rows.iter()).position(|r| r.len() != width || r.iter().any(|v| !v.is_finite()))
    {
        return refuse(format!(
            "rows of {width} finite numbers (row {}: {:?})",
            k + 1,
            rows[k]
        ));
    }
    if rows.len() < 2 || width < 2 {
        return refuse("at least two rows of a time and a value".into());
    }
    let t: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    if let Some(k) = (1..t.len()).find(|&k| t[k] <= t[k - 1]) {
        return refuse(format!(
            "times that increase (row {} has t = {} after {})",
            k + 1,
            t[k],
            t[k - 1]
        ));
    }
    if t[0] > 0.0 || t[t.len() - 1] < end {
        return refuse(format!(
            "a table that covers the run, t = 0 to {end} s (it covers {} to {} s)",
            t[0],
            t[t.len() - 1]
        ));
    }
    let columns = (1..width)
        .map(|c| rows.iter().map(|r| r[c]).collect())
        .collect();
    Ok((t, columns))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spline_is_exact_for_lines_and_c2_at_its_knots() {
        let g = |t: f64| t * (2.0 - t) * (1.0 + t * (2.0 - t)); // symmetric quartic
        let t: Vec<f64> = (0..=20).map(|k| 0.1 * k as f64).collect();
        let s = Spline::new(t.clone(), t.iter().map(|&t| 2.0 * t + 1.0).collect());
        let [v, d, dd] = s.at(0.73);
        assert!((v - 2.46).abs() < 1e-14 && (d - 2.0).abs() < 1e-13 && dd.abs() < 1e-12);
        // a smooth signal: value, slope and curvature converge, curvature continuous at knots
        let s = Spline::new(t.clone(), t.iter().map(|&t| g(t)).collect());
        let [v, d, _] = s.at(1.05);
        let h = 1e-6;
        assert!((v - g(1.05)).abs() < 1e-4, "{v}");
        assert!(
            (d - (g(1.05 + h) - g(1.05 - h)) / (2.0 * h)).abs() < 2e-3,
            "{d}"
        );
        let (below, above) = (s.at(0.7 - 1e-12), s.at(0.7 + 1e-12));
        assert!((below[2] - above[2]).abs() < 1e-9 && (below[1] - above[1]).abs() < 1e-9);
    }

    #[test]
    fn bad_tables_are_refused_in_one_line() {
        let dir = std::env::temp_dir().join(format!("motion_table_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let read = |name: &str, text: &str, end: f64| {
            let path = dir.join(name);
            std::fs::write(&path, text).unwrap();
            read_columns("wall[0].prescribed.table", &path, end).map_err(|e| e.to_string())
        };
        let (t, c) = read(
            "ok.csv",
            "t, x, y\n# a comment\n0, 0, 0\n0.5 0.1 0\n1.0,0.2,0.0\n",
            1.0,
        )
        .unwrap();
        assert_eq!(t, vec![0.0, 0.5, 1.0]);
        assert_eq!(c, vec![vec![0.0, 0.1, 0.2], vec![0.0, 0.0, 0.0]]);
        let e = read("short.csv", "0, 0, 0\n1, 1\n", 1.0).unwrap_err();
        assert!(
            e.contains("expected rows of 3 finite numbers (row 2: [1.0, 1.0])"),
            "{e}"
        );
        let e = read("words.csv", "0, 0\n1, one\n", 1.0).unwrap_err();
        assert!(
            e.contains("expected rows of numbers (line 2: \"1, one\")"),
            "{e}"
        );
        let e = read("back.csv", "0, 0\n1, 1\n0.5, 2\n", 0.5).unwrap_err();
        assert!(
            e.contains("expected times that increase (row 3 has t = 0.5 after 1)"),
            "{e}"
        );
        let e = read("end.csv", "0, 0\n1, 1\n", 2.0).unwrap_err();
        assert!(
            e.contains("expected a table that covers the run, t = 0 to 2 s"),
            "{e}"
        );
        let e = read("nan.csv", "0, 0\n1, nan\n", 1.0).unwrap_err();
        assert!(e.contains("finite numbers (row 2"), "{e}");
        let rows = [vec![0.0, 0.0], vec![1.0, 1.0], vec![0.5, 2.0]];
        let e = columns("shape[0].prescribed.table", "3 rows", &rows, 0.5).unwrap_err();
        assert_eq!(
            e.to_string(),
            "shape[0].prescribed.table = 3 rows: expected times that increase (row 3 has t = 0.5 after 1)"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
