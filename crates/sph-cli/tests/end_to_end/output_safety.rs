//! Nothing a user owns is lost: `--force` removes only what deltasph wrote, a folder
//! that is not a run folder is never used, and a case name cannot point outside the
//! working folder.

use crate::common::{cli, scratch, small_case};
use std::fs;
use std::path::Path;
use std::process::Command;

fn run_in(cwd: &Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("sph-cli runs")
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn force_replaces_the_earlier_run_and_keeps_the_users_files() {
    let dir = scratch("force_keeps");
    let case = small_case(&dir, "");
    let run = dir.join("run");
    let first = cli(&["run", &case, "--out", run.to_str().unwrap(), "--quiet"]);
    assert!(first.status.success(), "{}", stderr(&first));
    fs::write(run.join("notes.txt"), "my notes").unwrap();
    fs::create_dir(run.join("plots")).unwrap();
    fs::write(run.join("plots").join("fig.png"), "png").unwrap();
    // a stale snapshot of the earlier run that the new one will not write again
    let stale = run.join("particles_000099.h5");
    fs::copy(run.join("particles_000000.h5"), &stale).unwrap();
    let manifest = run.join(".deltasph-run");
    let listed = fs::read_to_string(&manifest).unwrap() + "particles_000099.h5\n";
    fs::write(&manifest, listed).unwrap();

    let again = cli(&[
        "run",
        &case,
        "--out",
        run.to_str().unwrap(),
        "--quiet",
        "--force",
    ]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(
        fs::read_to_string(run.join("notes.txt")).unwrap(),
        "my notes"
    );
    assert_eq!(
        fs::read_to_string(run.join("plots").join("fig.png")).unwrap(),
        "png"
    );
    assert!(!stale.exists(), "the earlier run's files are removed");
    assert!(run.join("particles.xmf").is_file() && run.join("restart.h5").is_file());
}

#[test]
fn a_folder_deltasph_did_not_create_is_refused_even_with_force() {
    let dir = scratch("foreign");
    let case = small_case(&dir, "");
    let home = dir.join("home");
    fs::create_dir_all(&home).unwrap();
    fs::write(home.join("thesis.tex"), "years of work").unwrap();
    for out in [".", "./"] {
        let refused = run_in(&home, &["run", &case, "--out", out, "--force", "--quiet"]);
        let err = stderr(&refused);
        assert_eq!(refused.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!(
                "error: output {out}: is not empty and is not a deltasph run folder"
            )),
            "{err}"
        );
    }
    let names: Vec<String> = fs::read_dir(&home)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["thesis.tex"], "nothing was added or removed");
    assert_eq!(
        fs::read_to_string(home.join("thesis.tex")).unwrap(),
        "years of work"
    );
}

#[test]
fn a_run_never_writes_over_a_file_it_did_not_write() {
    let dir = scratch("no_overwrite");
    let case = small_case(&dir, "");
    let run = dir.join("run");
    assert!(
        cli(&["run", &case, "--out", run.to_str().unwrap(), "--quiet"])
            .status
            .success()
    );
    // the user replaces the manifest's knowledge: a file of theirs where the next run
    // will want to write its time series
    let manifest = run.join(".deltasph-run");
    let text = fs::read_to_string(&manifest)
        .unwrap()
        .replace("timeseries.csv\n", "");
    fs::write(&manifest, text).unwrap();
    fs::write(run.join("timeseries.csv"), "my data").unwrap();
    let out = cli(&[
        "run",
        &case,
        "--out",
        run.to_str().unwrap(),
        "--quiet",
        "--force",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("timeseries.csv: exists and was not written by deltasph"),
        "{err}"
    );
    assert_eq!(
        fs::read_to_string(run.join("timeseries.csv")).unwrap(),
        "my data"
    );
}

#[test]
fn a_name_that_is_a_path_is_refused_and_writes_nothing() {
    let dir = scratch("bad_name");
    let work = dir.join("work");
    fs::create_dir_all(&work).unwrap();
    for name in ["../escaped", "/tmp/absolute", ".."] {
        let case = small_case(&dir, "");
        let text = fs::read_to_string(&case).unwrap();
        let text = text.replace("name = \"dam_break_2d\"", &format!("name = {name:?}"));
        fs::write(&case, text).unwrap();
        let out = run_in(&work, &["run", &case, "--quiet", "--force"]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.starts_with(&format!(
                "error: name = {name:?}: expected a plain file name"
            )),
            "{err}"
        );
    }
    assert!(!dir.join("escaped_out").exists() && !Path::new("/tmp/absolute_out").exists());
    assert_eq!(fs::read_dir(&work).unwrap().count(), 0);
}
