#include "core/case_node.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <sstream>

#include "core/case_text.h"
#include "core/printable.h"

namespace mpm_lig {
namespace {

//! A short description of a value for a message: small values as JSON, large ones by their
//! kind and size (a message never grows with the input).
std::string describe(const nlohmann::json& j) {
  if (j.is_object())
    return "an object with " + std::to_string(j.size()) + " keys";
  if (j.is_array()) {
    const bool flat = j.size() <= 6 && std::none_of(j.begin(), j.end(), [](const auto& v) {
                        return v.is_structured();
                      });
    if (!flat)
      return "an array of " + std::to_string(j.size()) + " values";
  }
  if (j.is_string() && j.get_ref<const std::string&>().size() > 60)
    return "\"" + printable(j.get_ref<const std::string&>(), 50) + "\"";
  std::string text = printable(j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  if (text.size() > 60)
    text = text.substr(0, 57) + "...";
  return text;
}

template <class T>
struct Reader;

template <>
struct Reader<double> {
  static const char* expected() { return "a number"; }
  static bool ok(const nlohmann::json& j) { return j.is_number(); }
  static double read(const nlohmann::json& j) { return j.get<double>(); }
};
template <>
struct Reader<long> {
  static const char* expected() { return "an integer"; }
  static bool ok(const nlohmann::json& j) {
    if (j.is_number_integer())
      return true;
    // Accept 4.0 but not 4.5: users write 1e4 for counts.
    if (j.is_number_float()) {
      const double v = j.get<double>();
      return v == static_cast<double>(static_cast<long>(v));
    }
    return false;
  }
  static long read(const nlohmann::json& j) {
    return j.is_number_integer() ? j.get<long>() : static_cast<long>(j.get<double>());
  }
};
template <>
struct Reader<int> {
  static const char* expected() { return "an integer"; }
  static bool ok(const nlohmann::json& j) {
    if (!Reader<long>::ok(j))
      return false;
    const long v = Reader<long>::read(j);
    return v >= std::numeric_limits<int>::min() && v <= std::numeric_limits<int>::max();
  }
  static int read(const nlohmann::json& j) { return static_cast<int>(Reader<long>::read(j)); }
};
template <>
struct Reader<bool> {
  static const char* expected() { return "true or false"; }
  static bool ok(const nlohmann::json& j) { return j.is_boolean(); }
  static bool read(const nlohmann::json& j) { return j.get<bool>(); }
};
template <>
struct Reader<std::string> {
  static const char* expected() { return "a string"; }
  static bool ok(const nlohmann::json& j) { return j.is_string(); }
  static std::string read(const nlohmann::json& j) { return j.get<std::string>(); }
};

template <class T>
T read_scalar(const nlohmann::json& j, const std::string& path) {
  if (!Reader<T>::ok(j)) {
    throw CaseError(path,
                    std::string("expected ") + Reader<T>::expected() + ", got " + describe(j));
  }
  return Reader<T>::read(j);
}

template <class T>
std::vector<T> read_vector(const nlohmann::json& j, const std::string& path) {
  if (!j.is_array()) {
    throw CaseError(path, std::string("expected an array of ") + Reader<T>::expected() + ", got " +
                              describe(j));
  }
  std::vector<T> out;
  out.reserve(j.size());
  for (std::size_t i = 0; i < j.size(); ++i)
    out.push_back(read_scalar<T>(j[i], json_path_index(path, i)));
  return out;
}

template <class T, std::size_t N>
std::array<T, N> read_array(const nlohmann::json& j, const std::string& path) {
  const std::vector<T> v = read_vector<T>(j, path);
  if (v.size() != N) {
    throw CaseError(path,
                    "expected " + std::to_string(N) + " values, got " + std::to_string(v.size()));
  }
  std::array<T, N> out{};
  for (std::size_t i = 0; i < N; ++i)
    out[i] = v[i];
  return out;
}

}  // namespace

std::string CaseNode::path_of(const std::string& key) const {
  return json_path_key(path_, key);
}

bool CaseNode::has(const std::string& key) const {
  return json_->is_object() && json_->contains(key);
}

const nlohmann::json& CaseNode::value(const std::string& key) const {
  if (!json_->is_object())
    fail("expected an object, got " + describe(*json_));
  auto it = json_->find(key);
  if (it == json_->end())
    fail(key, "required key is missing");
  usage_->used_paths.insert(path_of(key));
  return *it;
}

#define MPM_LIG_CASE_GET(T)                                                        \
  template <>                                                                      \
  T CaseNode::get<T>(const std::string& key) const {                               \
    return read_scalar<T>(value(key), path_of(key));                               \
  }                                                                                \
  template <>                                                                      \
  std::vector<T> CaseNode::get<std::vector<T>>(const std::string& key) const {     \
    return read_vector<T>(value(key), path_of(key));                               \
  }                                                                                \
  template <>                                                                      \
  std::array<T, 2> CaseNode::get<std::array<T, 2>>(const std::string& key) const { \
    return read_array<T, 2>(value(key), path_of(key));                             \
  }                                                                                \
  template <>                                                                      \
  std::array<T, 3> CaseNode::get<std::array<T, 3>>(const std::string& key) const { \
    return read_array<T, 3>(value(key), path_of(key));                             \
  }                                                                                \
  template <>                                                                      \
  std::array<T, 6> CaseNode::get<std::array<T, 6>>(const std::string& key) const { \
    return read_array<T, 6>(value(key), path_of(key));                             \
  }
MPM_LIG_CASE_GET(double)
MPM_LIG_CASE_GET(int)
MPM_LIG_CASE_GET(long)
MPM_LIG_CASE_GET(bool)
MPM_LIG_CASE_GET(std::string)
#undef MPM_LIG_CASE_GET

std::string CaseNode::file_path(const std::string& key) const {
  const std::filesystem::path name = get<std::string>(key);
  if (name.empty())
    fail(key, "empty file name");
  if (name.is_absolute() || usage_->base_dir.empty())
    return name.string();
  return (std::filesystem::path(usage_->base_dir) / name).lexically_normal().string();
}

double CaseNode::positive(const std::string& key) const {
  const double v = get<double>(key);
  if (!(v > 0.0))
    fail(key, "must be > 0, got " + describe(value(key)));
  return v;
}
double CaseNode::positive_or(const std::string& key, double fallback) const {
  return has(key) ? positive(key) : fallback;
}
double CaseNode::non_negative(const std::string& key) const {
  const double v = get<double>(key);
  if (!(v >= 0.0))
    fail(key, "must be >= 0, got " + describe(value(key)));
  return v;
}
double CaseNode::non_negative_or(const std::string& key, double fallback) const {
  return has(key) ? non_negative(key) : fallback;
}
double CaseNode::in_range(const std::string& key, double lo, double hi) const {
  const double v = get<double>(key);
  if (!(v >= lo && v <= hi)) {
    std::ostringstream msg;
    msg << "must be in [" << lo << ", " << hi << "], got " << describe(value(key));
    fail(key, msg.str());
  }
  return v;
}
double CaseNode::in_range_or(const std::string& key, double lo, double hi, double fallback) const {
  return has(key) ? in_range(key, lo, hi) : fallback;
}

std::string CaseNode::choice(const std::string& key,
                             const std::vector<std::string>& choices) const {
  const std::string v = get<std::string>(key);
  for (const auto& c : choices) {
    if (c == v)
      return v;
  }
  std::string list;
  for (const auto& c : choices)
    list += (list.empty() ? "\"" : ", \"") + c + "\"";
  fail(key, "unknown value \"" + v + "\"; expected one of " + list);
}
std::string CaseNode::choice_or(const std::string& key, const std::vector<std::string>& choices,
                                const std::string& fallback) const {
  return has(key) ? choice(key, choices) : fallback;
}

CaseNode CaseNode::child(const std::string& key) const {
  const nlohmann::json& j = value(key);
  if (!j.is_object())
    fail(key, "expected an object, got " + describe(j));
  return CaseNode(&j, path_of(key), usage_);
}

std::vector<CaseNode> CaseNode::children(const std::string& key) const {
  const nlohmann::json& j = value(key);
  if (!j.is_array())
    fail(key, "expected an array, got " + describe(j));
  std::vector<CaseNode> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    out.push_back(CaseNode(&j[i], json_path_index(path_of(key), i), usage_));
  }
  return out;
}

void CaseNode::fail(const std::string& key, const std::string& message) const {
  throw CaseError(path_of(key), message);
}
void CaseNode::fail(const std::string& message) const {
  throw CaseError(path_.empty() ? "(root)" : path_, message);
}

CaseDocument::CaseDocument(nlohmann::json json)
    : json_(std::make_shared<const nlohmann::json>(std::move(json))),
      usage_(std::make_shared<CaseNode::Usage>()) {}

CaseDocument CaseDocument::parse(const std::string& text) {
  check_case_text(text);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text, nullptr, true, /*ignore_comments=*/false);
  } catch (const nlohmann::json::exception& e) {
    // check_case_text() has seen every error the parser can find; this is a last guard.
    throw CaseError("(file)", std::string("not valid JSON: ") + printable(e.what(), 300));
  }
  if (!j.is_object())
    throw CaseError("(root)", "a case file must be a JSON object");
  return CaseDocument(std::move(j));
}

CaseDocument CaseDocument::load(const std::string& filename) {
  CaseDocument document = parse(read_case_text(filename));
  document.usage_->base_dir = std::filesystem::path(filename).parent_path().string();
  return document;
}

CaseNode CaseDocument::root() const {
  return CaseNode(json_.get(), "", usage_);
}

namespace {
void find_unused(const nlohmann::json& j, const std::string& path,
                 const std::set<std::string>& used) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      // Keys starting with '_' are comments ("_note": "..."), ignored by design.
      if (!it.key().empty() && it.key()[0] == '_')
        continue;
      const std::string p = json_path_key(path, it.key());
      if (!used.count(p))
        throw CaseError(p, "unknown key (misspelt, or not used by this case)");
      find_unused(it.value(), p, used);
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i)
      find_unused(j[i], json_path_index(path, i), used);
  }
}
}  // namespace

void CaseDocument::check_all_used() const {
  find_unused(*json_, "", usage_->used_paths);
}

}  // namespace mpm_lig
