//! The points a measurement reads: listed in a file, spaced evenly on a segment, or
//! on the nodes of a box grid. Each point is a list of coordinates; the measurement
//! checks that it has the case's dimension.

use crate::error::{Result, SphError};
use std::path::Path;

/// The most points one measurement reads (each read at every snapshot).
pub const MAX_POINTS: usize = 1_000_000;

/// `n >= 2` points evenly spaced from `a` to `b`, both ends included.
pub fn line(a: &[f64], b: &[f64], n: usize) -> Result<Vec<Vec<f64>>> {
    let text = || format!("{a:?} {b:?} {n}");
    if a.len() != b.len() || !(2..=MAX_POINTS).contains(&n) {
        return Err(SphError::invalid(
            "line",
            text(),
            format!("two ends with the same number of coordinates and 2 to {MAX_POINTS} points"),
        ));
    }
    Ok((0..n)
        .map(|k| {
            let s = k as f64 / (n - 1) as f64;
            a.iter().zip(b).map(|(a, b)| a + s * (b - a)).collect()
        })
        .collect())
}

/// The nodes of the box `lo`–`hi` with `counts[d]` nodes along axis d (ends included;
/// one node sits at `lo[d]`), the first axis varying fastest.
pub fn grid(lo: &[f64], hi: &[f64], counts: &[usize]) -> Result<Vec<Vec<f64>>> {
    let total = counts.iter().try_fold(1usize, |t, &c| t.checked_mul(c));
    let fits = total.is_some_and(|t| (1..=MAX_POINTS).contains(&t));
    if lo.len() != hi.len() || lo.len() != counts.len() || !fits {
        return Err(SphError::invalid(
            "grid",
            format!("{lo:?} {hi:?} {counts:?}"),
            format!(
                "two corners and a node count per axis, as many as the corners have \
                 coordinates, each at least 1, at most {MAX_POINTS} nodes in all"
            ),
        ));
    }
    let axis = |d: usize, k: usize| match counts[d] {
        1 => lo[d],
        c => lo[d] + (hi[d] - lo[d]) * k as f64 / (c - 1) as f64,
    };
    Ok((0..total.unwrap_or(0))
        .map(|mut flat| {
            (0..counts.len())
                .map(|d| {
                    let k = flat % counts[d];
                    flat /= counts[d];
                    axis(d, k)
                })
                .collect()
        })
        .collect())
}

/// The points of a text file: a point per line, its coordinates separated by commas
/// or blanks; blank lines and lines starting with `#` are skipped.
pub fn read_file(path: &Path) -> Result<Vec<Vec<f64>>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SphError::output(path, format!("unreadable points file ({e})")))?;
    let mut points = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let coordinates: std::result::Result<Vec<f64>, _> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|s| !s.is_empty())
            .map(str::parse)
            .collect();
        match coordinates {
            Ok(c) if !c.is_empty() && points.len() < MAX_POINTS => points.push(c),
            _ => {
                return Err(SphError::output(
                    path,
                    format!(
                        "line {}: `{line}` is not a point (expected its coordinates as \
                         numbers separated by commas or blanks, at most {MAX_POINTS} points)",
                        k + 1
                    ),
                ))
            }
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_include_both_ends() {
        let points = line(&[0.0, 1.0], &[1.0, 0.0], 5).unwrap();
        assert_eq!(points.len(), 5);
        assert_eq!(points[0], vec![0.0, 1.0]);
        assert_eq!(points[2], vec![0.5, 0.5]);
        assert_eq!(points[4], vec![1.0, 0.0]);
        assert!(line(&[0.0], &[1.0], 1).is_err());
        assert!(line(&[0.0, 0.0], &[1.0], 3).is_err());
    }

    #[test]
    fn grids_vary_the_first_axis_fastest() {
        let points = grid(&[0.0, 0.0], &[1.0, 2.0], &[3, 2]).unwrap();
        let expected = [
            [0.0, 0.0],
            [0.5, 0.0],
            [1.0, 0.0],
            [0.0, 2.0],
            [0.5, 2.0],
            [1.0, 2.0],
        ];
        assert_eq!(points, expected.map(|p| p.to_vec()));
        assert_eq!(
            grid(&[0.0, 0.3], &[1.0, 0.3], &[2, 1]).unwrap()[1],
            vec![1.0, 0.3]
        );
        assert!(grid(&[0.0, 0.0], &[1.0, 1.0], &[0, 3]).is_err());
        assert!(grid(&[0.0, 0.0], &[1.0, 1.0], &[usize::MAX, 3]).is_err());
    }

    #[test]
    fn files_take_commas_blanks_and_comments_and_name_a_bad_line() {
        let dir = std::env::temp_dir().join(format!("points-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let good = dir.join("good.csv");
        std::fs::write(&good, "# x, y\n0.5, 0.1\n\n1 0.2\n").unwrap();
        let bad = dir.join("bad.csv");
        std::fs::write(&bad, "0.5,0.1\nx,y\n").unwrap();
        let (read_good, read_bad) = (read_file(&good), read_file(&bad));
        std::fs::remove_file(good).unwrap();
        std::fs::remove_file(bad).unwrap();
        std::fs::remove_dir(dir).unwrap();
        assert_eq!(read_good.unwrap(), vec![vec![0.5, 0.1], vec![1.0, 0.2]]);
        let message = read_bad.unwrap_err().to_string();
        assert!(
            message.contains("line 2: `x,y` is not a point"),
            "{message}"
        );
    }
}
