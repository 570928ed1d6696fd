#include "coupling/point_checkpoint.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>

#include "coupling/rve_state_fields.h"

namespace mpm_lig::coupling {
namespace {

//! One named field of PointCheckpoint: its width and where its values live. A field that
//! gained values at its end also reads the narrower rows earlier builds wrote (`oldest_width`),
//! the values they lack zero.
struct Field {
  const char* name;
  std::size_t width;
  std::function<double*(PointCheckpoint&)> at;
  std::size_t oldest_width = 0;  //!< 0: only `width`
};

//! The fields in their order on disk; the RVE's state is kRveStateFields, the table a moving
//! RVE's state goes by too.
std::vector<Field> make_fields() {
  std::vector<Field> fields{
      {"stress", 9, [](PointCheckpoint& p) { return p.stress.data(); }},
      {"dem_substeps", 1, [](PointCheckpoint& p) { return &p.substeps; }},
  };
  for (const RveStateField& f : kRveStateFields)
    fields.push_back({f.name, f.width, [at = f.at](PointCheckpoint& p) { return at(p.rve); }});
  fields.push_back({"dem_work", DemWork::kValues, [](PointCheckpoint& p) { return p.work; }});
  // 33 before the yielding flag (cap_friction) was added.
  fields.push_back(
      {"quiet_points", QuietPoints::kValues, [](PointCheckpoint& p) { return p.quiet; }, 33});
  fields.push_back({"steady_flow", SteadyFlow::kValues, [](PointCheckpoint& p) { return p.flow; }});
  return fields;
}

const std::vector<Field>& fields() {
  static const std::vector<Field> table = make_fields();
  return table;
}

constexpr const char* kFieldCount = "point_fields";

}  // namespace

std::size_t point_checkpoint_width() {
  std::size_t width = 0;
  for (const Field& f : fields())
    width += f.width;
  return width;
}

void pack(const PointCheckpoint& p, std::vector<double>& row) {
  PointCheckpoint copy = p;
  for (const Field& f : fields()) {
    const double* values = f.at(copy);
    row.insert(row.end(), values, values + f.width);
  }
}

PointCheckpoint unpack(const double* row) {
  PointCheckpoint p;
  for (const Field& f : fields()) {
    std::copy(row, row + f.width, f.at(p));
    row += f.width;
  }
  return p;
}

void write_points(materials::CheckpointWriter& out, const std::vector<double>& rows) {
  const std::size_t width = point_checkpoint_width();
  const std::size_t points = rows.size() / width;
  std::size_t offset = 0;
  for (const Field& f : fields()) {
    std::vector<double> values;
    values.reserve(points * f.width);
    for (std::size_t p = 0; p < points; ++p) {
      const double* row = rows.data() + p * width + offset;
      values.insert(values.end(), row, row + f.width);
    }
    out.write(f.name, values);
    offset += f.width;
  }
  out.write(kFieldCount, {static_cast<double>(fields().size())});
}

std::vector<double> read_points(const materials::CheckpointReader& in, std::size_t points) {
  const auto mismatch = [&](const std::string& what) {
    return std::runtime_error(in.describe() + ": the DEM point fields do not match this mpm_lig (" +
                              what + "); resume with the version that wrote it");
  };
  if (!in.has(kFieldCount))
    throw mismatch("it names no fields");
  const std::vector<double> count = in.read(kFieldCount);
  if (count.size() != 1 || count[0] != static_cast<double>(fields().size()))
    throw mismatch("it has " + std::to_string(count.empty() ? 0L : static_cast<long>(count[0])) +
                   " fields, this version " + std::to_string(fields().size()));
  const std::size_t width = point_checkpoint_width();
  std::vector<double> rows(points * width);
  std::size_t offset = 0;
  for (const Field& f : fields()) {
    if (!in.has(f.name))
      throw mismatch(std::string("no field '") + f.name + "'");
    const std::vector<double> values = in.read(f.name);
    const bool older = f.oldest_width > 0 && values.size() == points * f.oldest_width;
    const std::size_t written = older ? f.oldest_width : f.width;
    if (values.size() != points * written)
      throw std::runtime_error(in.describe() + " holds " + std::to_string(values.size() / f.width) +
                               " DEM points, the case has " + std::to_string(points));
    for (std::size_t p = 0; p < points; ++p)
      std::copy_n(values.data() + p * written, written, rows.data() + p * width + offset);
    offset += f.width;
  }
  return rows;
}

}  // namespace mpm_lig::coupling
