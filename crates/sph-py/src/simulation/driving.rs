//! How a [`PySimulation`] is built and driven: construction from a case, stepping to a
//! target with the interpreter released, the run folder, and the failure and pressure
//! bookkeeping between calls.

use super::{PySimulation, Solver};
use crate::errors::to_py;
use crate::folder::{Folder, FolderOptions};
use crate::stepping::{advance, Target};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use sph_core::{Case, Simulation};

impl PySimulation {
    pub(super) fn build(py: Python<'_>, case: Case) -> PyResult<Self> {
        let solver = py
            .detach(|| match case.dimension {
                2 => Simulation::<2>::new(case).map(Solver::Two),
                _ => Simulation::<3>::new(case).map(Solver::Three),
            })
            .map_err(|e| to_py(py, e))?;
        Ok(Self::holding(solver, true, Folder::default()))
    }

    pub(super) fn holding(solver: Solver, pressure_fresh: bool, folder: Folder) -> Self {
        Self {
            solver,
            pressure_fresh,
            folder,
            failed: None,
            notices_shown: 0,
        }
    }

    /// After stepping: the solver's new notices as Python warnings, and a stop by the
    /// stability guard remembered (`failed`).
    pub(super) fn settle(&mut self, py: Python<'_>, outcome: PyResult<()>) -> PyResult<()> {
        let notices: Vec<String> =
            each!(&self.solver, s => s.notices()[self.notices_shown..].to_vec());
        self.notices_shown += notices.len();
        for notice in notices {
            let warning = py.get_type::<pyo3::exceptions::PyUserWarning>();
            PyErr::warn(py, &warning, &std::ffi::CString::new(notice)?, 1)?;
        }
        if let Err(e) = &outcome {
            if e.get_type(py).name()? == "InstabilityError" {
                self.failed = Some(e.value(py).str()?.to_cow()?.into_owned());
            }
        }
        outcome
    }

    /// Refuses to step a run the guard has stopped.
    pub(super) fn check_not_failed(&self) -> PyResult<()> {
        match &self.failed {
            Some(message) => Err(PyValueError::new_err(format!(
                "the stability guard stopped this simulation ({message}); its state is not \
                 physical and cannot be stepped on"
            ))),
            None => Ok(()),
        }
    }

    /// Steps to `until` writing the run folder `options.out`.
    pub(super) fn drive_folder(
        &mut self,
        py: Python<'_>,
        until: f64,
        output_interval: Option<f64>,
        options: &FolderOptions,
        report: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let folder = &mut self.folder;
        let outcome = each!(&mut self.solver, s => {
            if until > s.time() {
                s.set_end(until).map_err(|e| to_py(py, e))?;
            }
            if let Some(every) = output_interval {
                s.set_output_interval(every).map_err(|e| to_py(py, e))?;
            }
            folder.drive(py, s, options, report)
        });
        // a run that ends normally or on Ctrl-C syncs the pressure as it closes; after
        // a blow-up or a failed write it may be stale
        self.pressure_fresh = outcome.is_ok();
        outcome
    }

    pub(super) fn case(&self) -> &Case {
        each!(&self.solver, s => &s.case())
    }

    pub(super) fn fresh_pressure(&mut self) {
        if !self.pressure_fresh {
            each!(&mut self.solver, s => s.sync_pressure());
            self.pressure_fresh = true;
        }
    }

    /// Steps to `target`, detached from the interpreter, in slices between which
    /// Ctrl-C is honoured and `report(time, n_steps)` is called.
    pub(super) fn drive(
        &mut self,
        py: Python<'_>,
        target: Target,
        report: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        loop {
            let solver = &mut self.solver;
            let outcome = py.detach(|| each!(solver, s => advance(s, target)));
            self.pressure_fresh = false;
            let done = outcome.map_err(|e| to_py(py, e))?;
            py.check_signals()?;
            if let Some(report) = report {
                report.call1((self.time(), self.n_steps()))?;
            }
            if done {
                return Ok(());
            }
        }
    }
}
