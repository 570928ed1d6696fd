#include "io/vtk_snapshot.h"

#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "io/checked_stream.h"

namespace mpm_lig::io {
namespace {

std::ofstream open_polydata(const std::string& filename, const std::string& title,
                            std::size_t points) {
  std::ofstream out(filename);
  if (!out)
    throw std::runtime_error("cannot write '" + filename + "'");
  out << std::setprecision(9);
  out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << points << " double\n";
  return out;
}

void write_point(std::ofstream& out, const Vec3& x) {
  out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
}

}  // namespace

void write_vtk_grains(const std::string& filename, const std::vector<Vec3>& centres,
                      const std::vector<double>& radii, const std::vector<Vec3>& velocities) {
  const std::size_t n = centres.size();
  std::ofstream out = open_polydata(filename, "mpm_lig RVE grains", n);
  for (const auto& x : centres)
    write_point(out, x);
  out << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i)
    out << "1 " << i << '\n';
  out << "POINT_DATA " << n << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (double r : radii)
    out << r << '\n';
  out << "VECTORS velocity double\n";
  for (const auto& v : velocities)
    write_point(out, v);
  close_checked(out, filename);
}

void write_vtk_lines(const std::string& filename, const std::vector<Vec3>& starts,
                     const std::vector<Vec3>& ends, const std::string& scalar_name,
                     const std::vector<double>& scalars) {
  const std::size_t n = starts.size();
  std::ofstream out = open_polydata(filename, "mpm_lig RVE " + scalar_name, 2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    write_point(out, starts[i]);
    write_point(out, ends[i]);
  }
  out << "LINES " << n << ' ' << 3 * n << '\n';
  for (std::size_t i = 0; i < n; ++i)
    out << "2 " << 2 * i << ' ' << 2 * i + 1 << '\n';
  out << "CELL_DATA " << n << "\nSCALARS " << scalar_name << " double 1\nLOOKUP_TABLE default\n";
  for (double s : scalars)
    out << s << '\n';
  close_checked(out, filename);
}

}  // namespace mpm_lig::io
