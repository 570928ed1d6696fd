#include "core/case_text.h"

#include <sys/stat.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case_error.h"
#include "core/printable.h"

namespace mpm_lig {
namespace {

using Json = nlohmann::json;

//! Longest piece of the offending input quoted in a message.
constexpr std::size_t kQuotedBytes = 60;

//! A SAX pass that only checks: it tracks the JSON path of every value and stops at the
//! first problem, before a document is built.
class TextChecker final : public nlohmann::json_sax<Json> {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& name) override {
    Frame& f = frames_.back();
    f.key = name;
    if (!f.keys.insert(name).second)
      throw CaseError(json_path_key(f.path, name),
                      "key given twice in one object (JSON would silently keep only one)");
    return true;
  }

  bool parse_error(std::size_t /*position*/, const std::string& last_token,
                   const nlohmann::detail::exception& error) override {
    if (error.id == 406) {  // out_of_range: a number a double cannot hold
      throw CaseError(path_of_next_value(), "number " + printable(last_token, kQuotedBytes) +
                                                " is beyond the range of a double (about 1.8e308)");
    }
    std::string what = error.what();
    const std::size_t tag_end = what.find("] ");
    if (tag_end != std::string::npos)
      what.erase(0, tag_end + 2);
    const std::string near = frames_.empty() ? "" : " (in " + path_of_next_value() + ")";
    throw CaseError("(file)", "not valid JSON" + near + ": " + printable(what, 300));
  }

 private:
  struct Frame {
    bool object = true;
    std::string path;  //!< "" for the root
    std::string key;   //!< object: the last key read
    std::size_t next_index = 0;
    std::set<std::string> keys;
  };

  std::string path_of_next_value() const {
    if (frames_.empty())
      return "(root)";
    const Frame& f = frames_.back();
    return f.object ? json_path_key(f.path, f.key) : json_path_index(f.path, f.next_index);
  }

  bool value() {
    if (!frames_.empty() && !frames_.back().object)
      ++frames_.back().next_index;
    return true;
  }

  bool open(bool object) {
    Frame f;
    f.object = object;
    f.path = frames_.empty() ? "" : path_of_next_value();
    if (frames_.size() >= static_cast<std::size_t>(kMaxCaseDepth))
      throw CaseError(f.path, "nested deeper than " + std::to_string(kMaxCaseDepth) + " levels");
    value();
    frames_.push_back(std::move(f));
    return true;
  }

  bool close() {
    frames_.pop_back();
    return true;
  }

  std::vector<Frame> frames_;
};

}  // namespace

std::string json_path_key(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string json_path_index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

std::string read_case_text(const std::string& filename) {
  const std::string name = "'" + printable(filename, 300) + "'";
  struct stat info {};
  // stat, not open: opening a pipe would wait for a writer.
  if (::stat(filename.c_str(), &info) != 0)
    throw CaseError("(file)", "cannot open case file " + name + ": " + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) {
    const char* kind = S_ISDIR(info.st_mode)    ? "a folder"
                       : S_ISFIFO(info.st_mode) ? "a pipe"
                                                : "a device";
    throw CaseError("(file)", "case file " + name + " is " + kind + ", not a regular file");
  }
  if (static_cast<std::size_t>(info.st_size) > kMaxCaseFileBytes)
    throw CaseError("(file)", "case file " + name + " has " + std::to_string(info.st_size) +
                                  " bytes; a case file has at most " +
                                  std::to_string(kMaxCaseFileBytes) + " (is it a case file?)");
  std::ifstream in(filename, std::ios::binary);
  if (!in)
    throw CaseError("(file)", "cannot open case file " + name + ": " + std::strerror(errno));
  // Read in pieces up to one byte past the limit: st_size is 0 for some special files.
  std::string text;
  std::vector<char> piece(1 << 16);
  while (text.size() <= kMaxCaseFileBytes && in) {
    in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    text.append(piece.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad())
    throw CaseError("(file)", "cannot read case file " + name);
  if (text.size() > kMaxCaseFileBytes)
    throw CaseError("(file)", "case file " + name + " has more than " +
                                  std::to_string(kMaxCaseFileBytes) + " bytes");
  return text;
}

void check_case_text(const std::string& text) {
  const std::size_t nul = text.find('\0');
  if (nul != std::string::npos)
    throw CaseError("(file)", "a NUL byte at offset " + std::to_string(nul) +
                                  ": not a text file (or a damaged one)");
  TextChecker checker;
  Json::sax_parse(text, &checker, Json::input_format_t::json, /*strict=*/true,
                  /*ignore_comments=*/false);
}

}  // namespace mpm_lig
