#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <mpi.h>
#include <nlohmann/json.hpp>

namespace mpm_lig::materials {

//! How the values of one key from several materials make the run's.
enum class Combine { sum, max, min };

//! How the ranks' values of a statistic make the run's.
enum class Ranks {
  replicated,  //!< the same on every rank, or this rank's own: rank 0's is written
  gathered,    //!< every rank's, written as a list in rank order (after Statistics::gather)
};

//! One named value a material reports: a run total so far (the material keeps it over the
//! steps and through a resume itself).
struct Statistic {
  std::string key;  //!< its path in summary.json, parts separated by '.' ("stepping.migrations")
  double value = 0.0;
  Combine combine = Combine::sum;
  Ranks ranks = Ranks::replicated;
  bool integer = false;  //!< written as a whole number (a count)
  bool written = true;   //!< false: a total that only derived entries read
  std::string when;      //!< written only while this key's total is > 0 (empty: always)
  //! On the progress line while the value is > 0 and `when` holds: a printf format of its rate
  //! per second times `progress_scale` (empty: not shown).
  std::string progress;
  double progress_scale = 1.0;
};

//! A statistic `key` = `value` that materials combine by `combine`, the rest at its defaults.
inline Statistic statistic(std::string key, double value, Combine combine = Combine::sum) {
  Statistic s;
  s.key = std::move(key);
  s.value = value;
  s.combine = combine;
  return s;
}

class Statistics;

//! An entry computed from the combined totals (a ratio, a share), written under `key`.
struct Derived {
  std::string key;
  //! From the combined totals; none: not written.
  std::function<std::optional<double>(const Statistics&)> value;
  std::string when;      //!< written only while this key's total is > 0 (empty: always)
  std::string progress;  //!< printf format of the value on the progress line (empty: not shown)
};

//! What a material reports about its run: named values and entries derived from them.
struct Report {
  std::vector<Statistic> values;
  std::vector<Derived> derived;
};

//! Reports merged by key, in the order their keys first came: the values combine by their
//! Combine (the first report of a key brings its value), a derived entry is the first report's.
//! Whoever writes the summary needs no key's name.
class Statistics {
 public:
  void add(const Report& report);
  //! Collective over `comm`: rank 0 gets every rank's value of each gathered statistic.
  void gather(MPI_Comm comm);
  //! The run's wall time, for derived entries that are shares of it.
  void set_wall_seconds(double seconds) { wall_seconds_ = seconds; }
  double wall_seconds() const { return wall_seconds_; }

  bool has(const std::string& key) const { return find(key) != nullptr; }
  //! The combined value of `key` (std::logic_error when no report holds it).
  double value(const std::string& key) const;
  //! Every rank's value of a gathered `key` (empty before gather(), and on ranks other than 0).
  const std::vector<double>& per_rank(const std::string& key) const;
  //! The values of the written keys under `prefix` ("time_split."), in their order.
  std::vector<double> values_under(const std::string& prefix) const;

  //! Every written value and derived entry into `summary` at its path.
  void write(nlohmann::json& summary) const;
  //! The progress line's items: rates of values since `before` over `seconds`, and derived
  //! values. Empty when none is shown.
  std::vector<std::string> progress(const Statistics& before, double seconds) const;

 private:
  struct Entry {
    Statistic statistic;
    std::vector<double> per_rank;
  };
  const Entry* find(const std::string& key) const;
  bool holds(const std::string& when) const;

  std::vector<Entry> entries_;
  std::vector<Derived> derived_;
  double wall_seconds_ = 0.0;
};

}  // namespace mpm_lig::materials
