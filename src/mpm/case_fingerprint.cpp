#include "mpm/case_fingerprint.h"

#include <set>

namespace mpm_lig::mpm {
namespace {

std::string member_path(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

//! `path` with every "[<digits>]" replaced by "[*]" (a '[' without ']', as a key may hold,
//! ends the replacing).
std::string generic(const std::string& path) {
  std::string out;
  for (std::size_t k = 0; k < path.size(); ++k) {
    out += path[k];
    if (path[k] != '[')
      continue;
    const std::size_t close = path.find(']', k);
    if (close == std::string::npos)
      return out + path.substr(k + 1);
    out += "*]";
    k = close;
  }
  return out;
}

//! Keys starting with '_' are comments: the case reader ignores them.
bool comment_key(const std::string& key) {
  return !key.empty() && key[0] == '_';
}

bool safe(const std::string& path) {
  const std::string g = generic(path);
  for (const std::string& key : keys_safe_to_change_on_resume()) {
    if (g == key || g.compare(0, key.size() + 1, key + ".") == 0)
      return true;
  }
  return false;
}

void collect(const nlohmann::json& a, const nlohmann::json& b, const std::string& path,
             std::vector<std::string>& out) {
  if (a.is_object() && b.is_object()) {
    std::set<std::string> keys;
    for (auto it = a.begin(); it != a.end(); ++it)
      keys.insert(it.key());
    for (auto it = b.begin(); it != b.end(); ++it)
      keys.insert(it.key());
    for (const std::string& key : keys) {
      if (comment_key(key))
        continue;
      const std::string p = member_path(path, key);
      // A key given on one side only: its leaves are what differs.
      const nlohmann::json none = (a.contains(key) ? a[key] : b[key]).is_object()
                                      ? nlohmann::json::object()
                                      : nlohmann::json();
      collect(a.contains(key) ? a[key] : none, b.contains(key) ? b[key] : none, p, out);
    }
    return;
  }
  if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (std::size_t k = 0; k < a.size(); ++k)
      collect(a[k], b[k], path + "[" + std::to_string(k) + "]", out);
    return;
  }
  if (a != b && !safe(path))
    out.push_back(path.empty() ? "(the whole case)" : path);
}

}  // namespace

const std::vector<std::string>& keys_safe_to_change_on_resume() {
  static const std::vector<std::string> keys = {
      "title",
      "analysis.end",
      "output.every",
      "output.history_every",
      "output.checkpoint_every",
      "output.rve_snapshots.every",
      "materials[*].rve.log_file",
  };
  return keys;
}

std::vector<std::string> changed_case_keys(const nlohmann::json& saved, const nlohmann::json& now) {
  std::vector<std::string> out;
  collect(saved, now, "", out);
  return out;
}

}  // namespace mpm_lig::mpm
