//! `sph-cli measure` on a finished run: the probes' and a section's columns read again
//! from the snapshots equal the run's own time series at the snapshot steps (to the series'
//! ten printed digits), and the output file obeys the output-safety rules.

use crate::common::{cli, scratch, small_case, small_run};

/// The CSV `text` as its header and rows of numbers.
fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap()
}

#[test]
fn measure_reads_the_probes_again_from_the_snapshots() {
    let dir = scratch("measure");
    let section =
        "\n[[diagnostics.sections]]\nname = \"foot\"\ncorners = [[1.3, -0.1], [1.3, 0.7]]\n";
    let case = small_case(&dir, section);
    // probes in the column, at its collapsing corner, and ahead of the water (dry)
    let text = std::fs::read_to_string(&case).unwrap().replace(
        "probes = [[3.2196, 0.12], [3.2196, 0.16]]",
        "probes = [[0.3, 0.12], [1.19, 0.3], [3.2196, 0.16]]",
    );
    std::fs::write(&case, text).unwrap();
    let run = dir.join("out");
    let run = run.to_str().unwrap();
    assert!(cli(&["run", &case, "--out", run, "--quiet"])
        .status
        .success());
    let points = dir.join("points.txt");
    let listed = "# the case's probes\n0.3, 0.12\n1.19 0.3\n3.2196,0.16\n";
    std::fs::write(&points, listed).unwrap();
    let (points, csv) = (points.to_str().unwrap(), dir.join("probes.csv"));
    let csv = csv.to_str().unwrap();
    let measure = |extra: &[&str]| {
        let mut args = vec!["measure", run, "--points", points, "--elevation", "1.0"];
        args.extend_from_slice(&["--section", "1.3,-0.1", "1.3,0.7"]);
        args.extend_from_slice(&["--fields", "pressure,velocity"]);
        cli(&[&args[..], extra].concat())
    };
    let measured = measure(&["--out", csv]);
    let err = String::from_utf8_lossy(&measured.stderr);
    assert!(measured.status.success(), "{err}");
    let (header, rows) = table(&std::fs::read_to_string(csv).unwrap());
    let series = std::fs::read_to_string(dir.join("out/timeseries.csv")).unwrap();
    let (names, series) = table(&series);
    assert_eq!(rows.len(), 4, "snapshots at t = 0, 0.02, 0.04 and the end");
    let mut compared = 0;
    for row in &rows {
        let step = row[column(&header, "step")];
        let Some(in_run) = series.iter().find(|r| r[column(&names, "step")] == step) else {
            continue;
        };
        for k in 0..3 {
            let ours = row[column(&header, &format!("point{k}_pressure"))];
            let theirs = in_run[column(&names, &format!("probe{k}_pressure"))];
            assert_eq!(ours.is_nan(), theirs.is_nan(), "step {step}, probe {k}");
            if !ours.is_nan() {
                let tolerance = 1e-9 * theirs.abs().max(1.0);
                assert!((ours - theirs).abs() <= tolerance, "{ours} {theirs}");
                compared += 1;
            }
        }
        assert!(row[column(&header, "line0_elevation")] > 0.0);
        for flow in ["volume_flow", "mass_flow"] {
            let ours = row[column(&header, &format!("section0_{flow}"))];
            let theirs = in_run[column(&names, &format!("foot_{flow}"))];
            assert!(
                (ours - theirs).abs() <= 1e-9 * theirs.abs().max(1e-3),
                "{flow}: {ours} {theirs}"
            );
        }
    }
    assert_eq!(
        compared,
        2 * 4,
        "two probes wet, one dry, at every snapshot"
    );
    assert!(header.contains(&"point1_v".to_string()));

    // the file is replaced only with --force, and only when the measure tool wrote it
    let again = measure(&["--out", csv]);
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    assert!(measure(&["--out", csv, "--force"]).status.success());
    let users = dir.join("users.csv");
    std::fs::write(&users, "time,mine\n").unwrap();
    let refused = measure(&["--out", users.to_str().unwrap(), "--force"]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("never overwritten"));
    assert_eq!(std::fs::read_to_string(&users).unwrap(), "time,mine\n");
}

#[test]
fn measure_refuses_bad_points_in_one_line() {
    let dir = scratch("measure-bad");
    let run = small_run(&dir);
    let run = run.as_str();
    for (args, expected) in [
        (
            vec!["--line", "0,0", "1,0,0", "3"],
            "line = [0.0, 0.0] [1.0, 0.0, 0.0] 3",
        ),
        (
            vec!["--line", "0,0,0", "1,0,0", "3"],
            "points[0] = [0.0, 0.0, 0.0]: expected 2",
        ),
        (
            vec!["--line", "0,0", "1,x", "3"],
            "--line = 1,x: expected numbers",
        ),
        (
            vec!["--grid", "0,0", "1,1", "0,3"],
            "--grid = 0: expected a whole number",
        ),
        (vec!["--elevation", "1,2"], "elevation[0] = [1.0, 2.0]"),
        (
            vec!["--line", "0,0", "1,0", "3", "--fields", "temperature"],
            "fields = temperature",
        ),
        (vec![], "measure = no points"),
        (
            vec!["--section", "0.5,0", "0.5,0"],
            "sections[0] = [[0.5, 0.0], [0.5, 0.0]]: expected corners spanning a segment",
        ),
        (
            vec!["--section", "0,0", "1,0", "2,0"],
            "--section = 0,0 1,0 2,0: expected 2 corners",
        ),
    ] {
        let mut all = vec!["measure", run];
        all.extend(args);
        let out = cli(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(expected), "expected `{expected}` in: {err}");
    }
    let out = cli(&[
        "measure",
        dir.to_str().unwrap(),
        "--line",
        "0,0",
        "1,0",
        "3",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("not a run folder"), "{err}");
    let loads = cli(&["measure", run, "--loads"]);
    let err = String::from_utf8_lossy(&loads.stderr);
    assert_eq!(loads.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("set `loads = true` under [diagnostics]"),
        "{err}"
    );
}
