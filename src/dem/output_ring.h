#pragma once

#include <cstdio>
#include <memory>
#include <string>

namespace mpm_lig::dem::detail {

//! An in-memory C stream that keeps the last `capacity` bytes written to it.
//!
//! Engines print through a `FILE*` (their "screen"). Giving them this stream instead of
//! `-screen none` keeps them silent while their last lines, including their own ERROR text,
//! remain available for error reports. Engines fclose their screen on error and on exit,
//! so the stream may die before this object: the text stays readable here.
class OutputRing {
 public:
  explicit OutputRing(std::size_t capacity = 64 * 1024);
  ~OutputRing();
  OutputRing(const OutputRing&) = delete;
  OutputRing& operator=(const OutputRing&) = delete;

  //! The stream to hand to the engine (unbuffered; owned by whoever fcloses it).
  FILE* stream() const { return stream_; }
  //! Append text that did not pass through the stream.
  void append(const std::string& text);
  //! Everything kept, oldest first.
  std::string text() const;

  struct State;  //!< shared with the stream's callbacks (output_ring.cpp)

 private:
  std::shared_ptr<State> state_;  // shared with the stream's callbacks
  FILE* stream_ = nullptr;
};

}  // namespace mpm_lig::dem::detail
