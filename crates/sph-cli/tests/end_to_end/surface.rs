//! `sph-cli surface` on a finished run: a mesh per snapshot and a collection listing
//! them in time order, and the output-safety rules (its own files replaced only with
//! --force, a folder holding a file it did not write refused, nothing removed).

use crate::common::{cli, scratch, small_run};

#[test]
fn surface_writes_a_mesh_per_snapshot_and_keeps_what_it_did_not_write() {
    let dir = scratch("surface");
    let run = small_run(&dir);
    let run = run.as_str();
    let first = cli(&["surface", run]);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let folder = dir.join("out/surface");
    let collection = std::fs::read_to_string(folder.join("surface.pvd")).unwrap();
    let listed: Vec<&str> = (collection.lines())
        .filter_map(|l| l.split("file=\"").nth(1)?.split('"').next())
        .collect();
    assert_eq!(
        listed.len(),
        4,
        "snapshots at t = 0, 0.02, 0.04 and the end"
    );
    for file in &listed {
        let mesh = std::fs::read_to_string(folder.join(file)).unwrap();
        // the water's outline: a closed polyline of many points
        let points: usize = (mesh.split("NumberOfPoints=\"").nth(1))
            .and_then(|s| s.split('"').next()?.parse().ok())
            .unwrap();
        assert!(points > 20, "{file}: {points} points");
        assert!(mesh.contains("Name=\"wall_fraction\""));
    }
    // again: refused without --force, done with it
    let again = cli(&["surface", run]);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    assert!(cli(&["surface", run, "--force"]).status.success());
    // a file the tool did not write is never overwritten, even with --force
    let notes = folder.join("notes.txt");
    std::fs::write(&notes, "mine").unwrap();
    let refused = cli(&["surface", run, "--force"]);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("notes.txt"));
    assert_eq!(std::fs::read_to_string(&notes).unwrap(), "mine");
    // bad input names the key
    let bad = cli(&[
        "surface",
        run,
        "--out",
        dir.join("s2").to_str().unwrap(),
        "--level",
        "1.5",
    ]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("level"));
}
