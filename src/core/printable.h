#pragma once

#include <cstddef>
#include <string>

namespace mpm_lig {

//! Longest message mpm_lig prints for one problem: a message that quotes user input (a file
//! name, an engine's output) stays readable whatever that input is.
inline constexpr std::size_t kMaxMessageBytes = 4000;

//! `text` made safe for a terminal and a log: valid UTF-8 and newlines and tabs kept, every
//! other control byte and every byte that is not valid UTF-8 written as \xNN; cut to at most
//! about `max_bytes` bytes (marked "...").
std::string printable(const std::string& text, std::size_t max_bytes = kMaxMessageBytes);

}  // namespace mpm_lig
