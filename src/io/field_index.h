#pragma once

#include <string>
#include <vector>

#include "io/xdmf_index.h"

namespace mpm_lig::io {

//! The output steps a FieldWriter file holds, read back from the HDF5 file itself, in step
//! order: what the XDMF index of that file must list. Used to continue the index of a
//! resumed run.
std::vector<XdmfStep> read_field_steps(const std::string& h5_path);

}  // namespace mpm_lig::io
