#include "dem/output_ring.h"

#include <stdexcept>

namespace mpm_lig::dem::detail {

struct OutputRing::State {
  std::string text;
  std::size_t capacity = 0;
  bool stream_open = true;

  void append(const char* data, std::size_t size) {
    text.append(data, size);
    // Trim in chunks (to half the capacity) so appending stays amortised O(1).
    if (text.size() > capacity)
      text.erase(0, text.size() - capacity / 2);
  }
};

namespace {

// The cookie owns one reference to the state until the engine fcloses the stream.
using StateRef = std::shared_ptr<void>;

ssize_t write_cookie(void* cookie, const char* data, size_t size) {
  auto* state = static_cast<OutputRing::State*>(static_cast<StateRef*>(cookie)->get());
  state->append(data, size);
  return static_cast<ssize_t>(size);
}

int close_cookie(void* cookie) {
  auto* ref = static_cast<StateRef*>(cookie);
  static_cast<OutputRing::State*>(ref->get())->stream_open = false;
  delete ref;
  return 0;
}

}  // namespace

OutputRing::OutputRing(std::size_t capacity) : state_(std::make_shared<State>()) {
  state_->capacity = capacity;
  auto* ref = new StateRef(state_);
  stream_ =
      fopencookie(ref, "w", cookie_io_functions_t{nullptr, write_cookie, nullptr, close_cookie});
  if (!stream_) {
    delete ref;
    throw std::runtime_error("fopencookie failed");
  }
  // Unbuffered: an engine that dies right after printing must not take its last line along.
  std::setvbuf(stream_, nullptr, _IONBF, 0);
}

OutputRing::~OutputRing() {
  if (state_->stream_open)
    std::fclose(stream_);
}

void OutputRing::append(const std::string& text) {
  state_->append(text.data(), text.size());
}

std::string OutputRing::text() const {
  return state_->text;
}

}  // namespace mpm_lig::dem::detail
