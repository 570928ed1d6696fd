#pragma once

#include <string>
#include <vector>

#include "core/tensor.h"

namespace mpm_lig::io {

//! Grains as points with a "radius" scalar and a "velocity" vector (legacy VTK polydata;
//! in ParaView use the Glyph filter, sphere glyphs scaled by radius).
void write_vtk_grains(const std::string& filename, const std::vector<Vec3>& centres,
                      const std::vector<double>& radii, const std::vector<Vec3>& velocities);

//! Line segments with one scalar per line (force chains: centre to centre, "force" magnitude;
//! in ParaView use the Tube filter with radius scaled by it).
void write_vtk_lines(const std::string& filename, const std::vector<Vec3>& starts,
                     const std::vector<Vec3>& ends, const std::string& scalar_name,
                     const std::vector<double>& scalars);

}  // namespace mpm_lig::io
