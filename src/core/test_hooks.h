#pragma once

namespace mpm_lig {

//! Fault injection for the tests of the failure and resume paths. Read once from the
//! environment when the program starts and handed down explicitly: nothing reads the
//! environment while a run is stepping.
struct TestHooks {
  //! MPM_LIG_KILL_AT_STEP=n: rank 0 kills itself with SIGKILL after MPM step n is recorded.
  long kill_at_step = -1;
  //! MPM_LIG_TERM_AT_STEP=n: rank 0 sends itself SIGTERM after MPM step n (a signal in that step),
  //! or after increment n of an element test.
  long term_at_step = -1;
  //! MPM_LIG_TERM_AT_PACKING=k: the rank preparing dem_rve packing k sends itself SIGTERM as it
  //! starts on it (a signal in the middle of the preparation).
  long term_at_packing = -1;
  //! MPM_LIG_FAULT_POINT=i: the rank owning dem_rve point i sends its engine an unknown command.
  long fault_point = -1;
  //! MPM_LIG_FAULT_UPDATE=u: ... at the u-th update of that material (default 1).
  long fault_update = 1;

  //! The points of a run where a hook may act.
  enum class Moment {
    step_recorded,    //!< MPM step or element-test increment `index` is recorded
    step_finished,    //!< MPM step `index` is done, its checkpoint included
    packing_started,  //!< this rank starts preparing dem_rve packing `index`
  };
  //! The one seam of the hooks: at `moment` of step / increment / packing `index` on `rank`,
  //! raises the signal the hooks ask for there (SIGTERM or SIGKILL); nothing otherwise.
  void at(Moment moment, long index, int rank) const;

  //! The hooks the environment asks for (none when the variables are not set).
  static TestHooks from_environment();
};

}  // namespace mpm_lig
