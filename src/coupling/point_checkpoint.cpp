#include "coupling/point_checkpoint.h"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

namespace mpm_lig::coupling {
namespace {

//! One named field of PointCheckpoint: its width and where its values live.
struct Field {
  const char* name;
  std::size_t width;
  double* (*at)(PointCheckpoint&);
};

const Field kFields[] = {
    {"stress", 9, [](PointCheckpoint& p) { return p.stress.data(); }},
    {"dem_substeps", 1, [](PointCheckpoint& p) { return &p.substeps; }},
    {"rotation", 9, [](PointCheckpoint& p) { return p.rve.rotation.data(); }},
    {"streaming", 9, [](PointCheckpoint& p) { return p.rve.streaming.data(); }},
    {"rve_particle_steps", 1, [](PointCheckpoint& p) { return &p.rve.particle_steps; }},
    {"last_mean_stress", 1, [](PointCheckpoint& p) { return &p.rve.last_mean_stress; }},
    {"dem_work", DemWork::kValues, [](PointCheckpoint& p) { return p.work; }},
    {"quiet_points", QuietPoints::kValues, [](PointCheckpoint& p) { return p.quiet; }},
};

constexpr const char* kFieldCount = "point_fields";

}  // namespace

std::size_t point_checkpoint_width() {
  std::size_t width = 0;
  for (const Field& f : kFields)
    width += f.width;
  return width;
}

void pack(const PointCheckpoint& p, std::vector<double>& row) {
  PointCheckpoint copy = p;
  for (const Field& f : kFields) {
    const double* values = f.at(copy);
    row.insert(row.end(), values, values + f.width);
  }
}

PointCheckpoint unpack(const double* row) {
  PointCheckpoint p;
  for (const Field& f : kFields) {
    std::copy(row, row + f.width, f.at(p));
    row += f.width;
  }
  return p;
}

void write_points(materials::CheckpointWriter& out, const std::vector<double>& rows) {
  const std::size_t width = point_checkpoint_width();
  const std::size_t points = rows.size() / width;
  std::size_t offset = 0;
  for (const Field& f : kFields) {
    std::vector<double> values;
    values.reserve(points * f.width);
    for (std::size_t p = 0; p < points; ++p) {
      const double* row = rows.data() + p * width + offset;
      values.insert(values.end(), row, row + f.width);
    }
    out.write(f.name, values);
    offset += f.width;
  }
  out.write(kFieldCount, {static_cast<double>(std::size(kFields))});
}

std::vector<double> read_points(const materials::CheckpointReader& in, std::size_t points) {
  const auto mismatch = [&](const std::string& what) {
    return std::runtime_error(in.describe() + ": the DEM point fields do not match this mpm_lig (" +
                              what + "); resume with the version that wrote it");
  };
  if (!in.has(kFieldCount))
    throw mismatch("it names no fields");
  const std::vector<double> count = in.read(kFieldCount);
  if (count.size() != 1 || count[0] != static_cast<double>(std::size(kFields)))
    throw mismatch("it has " + std::to_string(count.empty() ? 0L : static_cast<long>(count[0])) +
                   " fields, this version " + std::to_string(std::size(kFields)));
  const std::size_t width = point_checkpoint_width();
  std::vector<double> rows(points * width);
  std::size_t offset = 0;
  for (const Field& f : kFields) {
    if (!in.has(f.name))
      throw mismatch(std::string("no field '") + f.name + "'");
    const std::vector<double> values = in.read(f.name);
    if (values.size() != points * f.width)
      throw std::runtime_error(in.describe() + " holds " + std::to_string(values.size() / f.width) +
                               " DEM points, the case has " + std::to_string(points));
    for (std::size_t p = 0; p < points; ++p)
      std::copy_n(values.data() + p * f.width, f.width, rows.data() + p * width + offset);
    offset += f.width;
  }
  return rows;
}

}  // namespace mpm_lig::coupling
