#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "io/csv_history.h"
#include "io/field_writer.h"
#include "mpm/checkpoint.h"
#include "mpm/solver.h"

namespace mpm_lig::mpm {

//! What the summary needs beyond the solver's state.
struct RunTotals {
  long gravity_stage_steps = 0;
  int ranks = 1;
  double wall_seconds = 0.0;  //!< the whole run, material preparation included
  //! Each rank's time in its RVEs (rank order; empty without MPI materials' cost).
  std::vector<double> dem_seconds_per_rank;
};

//! The materials' cost counters added up (DEM RVEs; zero for continuum materials).
materials::MaterialCost total_cost(const MaterialSet& materials);
//! Σ work / (groups × Σ_steps busiest group's work) of measured particle-steps (1 without any).
double stepping_efficiency(const materials::SteppingCost& s);

//! What an MPM run writes into its output folder: history.csv (every `history_every`
//! steps), results.h5/.xdmf (every `output_every` steps), one progress line per output
//! interval, and summary.json at the end.
template <int D>
class Recorder {
 public:
  //! With `resume`, continues the files of a resumed run: history.csv is cut to the
  //! checkpoint's rows, results.h5 loses the steps after it.
  Recorder(const MpmCase& c, const Solver<D>& solver, const std::string& directory,
           long total_steps, const RecorderState* resume = nullptr);

  //! What a checkpoint saves.
  RecorderState state() const { return {history_rows_, peak_bearing_pressure_}; }

  //! Called after every main-stage step (and once before the first).
  void after_step(const Solver<D>& solver);
  //! Write summary.json: run size, wall time and its split (DEM, MPM, communication, ...).
  void finish(const Solver<D>& solver, const RunTotals& totals);

  //! Column names of history.csv.
  static std::vector<std::string> history_columns(const MpmCase& c);
  //! One row of history.csv for the solver's current state.
  static std::vector<double> history_row(const Solver<D>& solver,
                                         const SimpleShearOutput& shear = {});

 private:
  void write_fields(const Solver<D>& solver);
  void print_progress(const Solver<D>& solver);

  std::string directory_;
  long output_every_, history_every_, total_steps_;
  std::vector<int> material_ids_;
  SimpleShearOutput simple_shear_;
  // Fields before history: a resume prepares results.h5 first, so that a failure there (full
  // disk) leaves history.csv untouched too.
  std::unique_ptr<io::FieldWriter> fields_;
  io::CsvHistory history_;
  std::chrono::steady_clock::time_point start_, last_;
  long last_step_ = 0;
  double last_particle_steps_ = 0.0;
  double output_seconds_ = 0.0;
  double peak_bearing_pressure_ = 0.0;
  long history_rows_ = 0;
};

}  // namespace mpm_lig::mpm
