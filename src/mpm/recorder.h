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
  //! The materials' statistics (MaterialSet::statistics), gathered over the ranks.
  materials::Statistics statistics;
};

//! What an MPM run writes into its output folder: history.csv (every `history_every`
//! steps), results.h5/.xdmf (every `output_every` steps), one progress line per output
//! interval, and summary.json at the end. The materials' statistics (materials/statistics.h)
//! go into the summary and the progress line by their own keys and formats.
template <int D>
class Recorder {
 public:
  //! With `resume`, continues the files of a resumed run: history.csv is cut to the
  //! checkpoint's rows, results.h5 loses the steps after it.
  Recorder(const MpmCase& c, const Solver<D>& solver, const std::string& directory,
           long total_steps, const RecorderState* resume = nullptr);

  //! What a checkpoint saves.
  RecorderState state() const {
    return {history_rows_, peak_bearing_pressure_, largest_stiffened_cfl_};
  }

  //! Called after every main-stage step (and once before the first).
  void after_step(const Solver<D>& solver);
  //! Write summary.json: run size, wall time and its split, the materials' statistics.
  void finish(const Solver<D>& solver, const RunTotals& totals);

  //! Column names of history.csv.
  static std::vector<std::string> history_columns(const MpmCase& c);
  //! One row of history.csv for the solver's current state.
  static std::vector<double> history_row(const Solver<D>& solver,
                                         const SimpleShearOutput& shear = {});

 private:
  void write_fields(const Solver<D>& solver);
  void print_progress(const Solver<D>& solver);
  void watch_stiffened_cfl(const Solver<D>& solver);

  std::string directory_;
  long output_every_, history_every_, total_steps_;
  std::vector<int> material_ids_;
  SimpleShearOutput simple_shear_;
  bool write_deformation_;  //!< output.deformation_gradient
  // Fields before history: a resume prepares results.h5 first, so that a failure there (full
  // disk) leaves history.csv untouched too.
  std::unique_ptr<io::FieldWriter> fields_;
  io::CsvHistory history_;
  std::chrono::steady_clock::time_point start_, last_;
  long last_step_ = 0;
  materials::Statistics last_statistics_;  //!< at the last progress line (rates since)
  double output_seconds_ = 0.0;
  double peak_bearing_pressure_ = 0.0;
  double largest_stiffened_cfl_ = 0.0;
  bool warned_stiffened_ = false;
  long history_rows_ = 0;
};

}  // namespace mpm_lig::mpm
