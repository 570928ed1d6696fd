#pragma once

#include <string>

namespace mpm_lig::mpm {

//! Names inside a run folder's `checkpoints/`:
//!
//!     checkpoints/latest               text: the name of the last complete step folder
//!     checkpoints/step_<n>/            one checkpoint (after MPM step n)
//!         mpm.h5, m<id>/... (a dem_rve: rank_<r>.bundle), case.json (the case it was
//!         written for), build, MANIFEST.sha256
//!
//! `latest` is the only name read from disk. It must be a plain `step_<n>`: a run never reads,
//! writes or deletes outside its folder because of a name it found inside it.
struct CheckpointFolder {
  static constexpr const char* kManifest = "MANIFEST.sha256";
  static constexpr const char* kCase = "case.json";
  static constexpr const char* kState = "mpm.h5";
  //! The identity of the build that wrote the checkpoint (core/build_id.h), one line.
  static constexpr const char* kBuild = "build";
  //! Layout of a checkpoint, kept in mpm.h5 ("format"; absent = 1). 2: a DEM point keeps its
  //! grains' exact placement beside its engine restart (point_<i>.restart.placement). 3: and
  //! its quiet-point state (the point field quiet_points, and the quiet_* run statistics).
  //! 4: and whether it is still its packing's continuum (a 33rd quiet_points value, and the
  //! continuum_* run statistics). 5: a dem_rve's points are members of one bundle per rank
  //! group, m<id>/rank_<r>.bundle, indexed in mpm.h5 (m<id>_bundle_index: rank, offset,
  //! length and SHA-256 of each point's restart and placement; docs/hpc.md §3) instead of
  //! two files per point. Format 4 is still read.
  static constexpr int kFormat = 5;
  //! The oldest layout this build resumes.
  static constexpr int kOldestFormat = 4;

  //! `run_dir/checkpoints`.
  static std::string root(const std::string& run_dir);
  //! "step_<n>".
  static std::string step_name(long step);
  //! Whether `name` is "step_" followed by digits only.
  static bool is_step_name(const std::string& name);
  //! The folder `latest` names (`run_dir/checkpoints/step_<n>`); throws ResumeError when there
  //! is no `latest`, it holds anything but a plain step name, or that folder is missing.
  static std::string latest(const std::string& run_dir);
  //! The step name in `latest`, or "" when there is none or it is not a plain step name.
  static std::string latest_name_or_empty(const std::string& run_dir);
};

}  // namespace mpm_lig::mpm
