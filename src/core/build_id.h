#pragma once

namespace mpm_lig {

//! This build's identity: `git describe --always --dirty` of the source tree it was built from,
//! or the project version outside a git checkout. Recorded in summaries and checkpoints, so
//! that results and resumes say which code computed them.
const char* build_id();

}  // namespace mpm_lig
