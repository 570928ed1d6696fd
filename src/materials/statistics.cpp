#include "materials/statistics.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <stdexcept>

namespace mpm_lig::materials {
namespace {

double combine(Combine how, double total, double value) {
  switch (how) {
    case Combine::max:
      return std::max(total, value);
    case Combine::min:
      return std::min(total, value);
    case Combine::sum:
      break;
  }
  return total + value;
}

//! The node of `summary` at the '.'-separated `path`, created where missing.
nlohmann::json& node_at(nlohmann::json& summary, const std::string& path) {
  nlohmann::json* node = &summary;
  std::size_t begin = 0;
  for (std::size_t dot = path.find('.'); dot != std::string::npos; dot = path.find('.', begin)) {
    node = &(*node)[path.substr(begin, dot - begin)];
    begin = dot + 1;
  }
  return (*node)[path.substr(begin)];
}

std::string format(const std::string& format, double value) {
  char text[160];
  std::snprintf(text, sizeof text, format.c_str(), value);
  return text;
}

}  // namespace

void Statistics::add(const Report& report) {
  for (const Statistic& s : report.values) {
    auto it = std::find_if(entries_.begin(), entries_.end(),
                           [&](const Entry& e) { return e.statistic.key == s.key; });
    if (it == entries_.end())
      entries_.push_back({s, {}});
    else
      it->statistic.value = combine(it->statistic.combine, it->statistic.value, s.value);
  }
  for (const Derived& d : report.derived) {
    if (std::none_of(derived_.begin(), derived_.end(),
                     [&](const Derived& known) { return known.key == d.key; }))
      derived_.push_back(d);
  }
}

void Statistics::gather(MPI_Comm comm) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  for (Entry& e : entries_) {
    if (e.statistic.ranks != Ranks::gathered)
      continue;
    std::vector<double> all(static_cast<std::size_t>(ranks));
    MPI_Gather(&e.statistic.value, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, 0, comm);
    if (rank == 0)
      e.per_rank = std::move(all);
  }
}

const Statistics::Entry* Statistics::find(const std::string& key) const {
  for (const Entry& e : entries_) {
    if (e.statistic.key == key)
      return &e;
  }
  return nullptr;
}

double Statistics::value(const std::string& key) const {
  const Entry* e = find(key);
  if (!e)
    throw std::logic_error("statistics: no report holds '" + key + "'");
  return e->statistic.value;
}

const std::vector<double>& Statistics::per_rank(const std::string& key) const {
  const Entry* e = find(key);
  if (!e)
    throw std::logic_error("statistics: no report holds '" + key + "'");
  return e->per_rank;
}

std::vector<double> Statistics::values_under(const std::string& prefix) const {
  std::vector<double> out;
  for (const Entry& e : entries_) {
    if (e.statistic.written && e.statistic.key.compare(0, prefix.size(), prefix) == 0)
      out.push_back(e.statistic.value);
  }
  return out;
}

bool Statistics::holds(const std::string& when) const {
  if (when.empty())
    return true;
  const Entry* e = find(when);
  return e && e->statistic.value > 0.0;
}

void Statistics::write(nlohmann::json& summary) const {
  for (const Entry& e : entries_) {
    const Statistic& s = e.statistic;
    if (!s.written || !holds(s.when))
      continue;
    if (s.ranks == Ranks::gathered) {
      if (!e.per_rank.empty())
        node_at(summary, s.key) = e.per_rank;
    } else if (s.integer) {
      node_at(summary, s.key) = static_cast<std::size_t>(s.value);
    } else {
      node_at(summary, s.key) = s.value;
    }
  }
  for (const Derived& d : derived_) {
    if (!holds(d.when))
      continue;
    if (const std::optional<double> v = d.value(*this))
      node_at(summary, d.key) = *v;
  }
}

std::vector<std::string> Statistics::progress(const Statistics& before, double seconds) const {
  std::vector<std::string> items;
  for (const Entry& e : entries_) {
    const Statistic& s = e.statistic;
    if (s.progress.empty() || !holds(s.when) || !(s.value > 0.0))
      continue;
    const double last = before.has(s.key) ? before.value(s.key) : 0.0;
    items.push_back(format(s.progress, (s.value - last) / seconds * s.progress_scale));
  }
  for (const Derived& d : derived_) {
    if (d.progress.empty() || !holds(d.when))
      continue;
    if (const std::optional<double> v = d.value(*this))
      items.push_back(format(d.progress, *v));
  }
  return items;
}

}  // namespace mpm_lig::materials
