#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace mpm_lig::io {

//! How a point field is laid out in the HDF5 file (see FieldWriter): `tensor` is a symmetric
//! tensor in six Voigt columns, `matrix` a general 3 x 3 tensor in nine row-major columns.
enum class XdmfKind { scalar, vector, tensor, matrix, integer };

struct XdmfField {
  std::string name;
  XdmfKind kind;
};

//! One output step as the XDMF index describes it.
struct XdmfStep {
  std::string group;  // HDF5 group, "step_000120"
  double time;
  std::size_t points;
  std::vector<XdmfField> fields;
};

//! XDMF 2 text: a temporal collection of Polyvertex grids whose data live in `h5_name`
//! (a path relative to the XDMF file), one grid per step.
std::string xdmf_text(const std::string& h5_name, const std::vector<XdmfStep>& steps);

}  // namespace mpm_lig::io
