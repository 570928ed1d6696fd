#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case_error.h"

namespace mpm_lig {

//! Strict, path-aware view of a part of a case file.
//!
//! Every read records the key as used; `CaseDocument::check_all_used()` then reports
//! any key nobody read as unknown, so that a typo never falls back silently to a default.
//! Every error is a CaseError naming the full JSON path (`materials[1].friction_deg`).
class CaseNode {
 public:
  //! The full path of this node ("" for the root).
  const std::string& path() const { return path_; }
  //! The full path of a child key of this node.
  std::string path_of(const std::string& key) const;

  bool has(const std::string& key) const;

  //! Required value of type T (double, int, long, bool, std::string, or a
  //! std::vector / std::array of those).
  template <class T>
  T get(const std::string& key) const;
  //! Optional value: `fallback` when the key is absent, a CaseError when present but wrong.
  template <class T>
  T get_or(const std::string& key, const T& fallback) const {
    return has(key) ? get<T>(key) : fallback;
  }

  //! Required file name; a relative name is taken relative to the case file's folder, so a
  //! case runs the same from any working directory.
  std::string file_path(const std::string& key) const;

  //! Required number > 0.
  double positive(const std::string& key) const;
  double positive_or(const std::string& key, double fallback) const;
  //! Required number >= 0.
  double non_negative(const std::string& key) const;
  double non_negative_or(const std::string& key, double fallback) const;
  //! Required number in [lo, hi].
  double in_range(const std::string& key, double lo, double hi) const;
  double in_range_or(const std::string& key, double lo, double hi, double fallback) const;
  //! Required string out of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const;
  std::string choice_or(const std::string& key, const std::vector<std::string>& choices,
                        const std::string& fallback) const;

  //! Required object child.
  CaseNode child(const std::string& key) const;
  //! The elements of a required array of objects (or of any JSON values).
  std::vector<CaseNode> children(const std::string& key) const;

  bool is_object() const { return json_->is_object(); }
  bool is_array() const { return json_->is_array(); }
  const nlohmann::json& json() const { return *json_; }

  //! Throw a CaseError for `key` of this node.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  //! Throw a CaseError for this node itself.
  [[noreturn]] void fail(const std::string& message) const;

 private:
  friend class CaseDocument;
  struct Usage {
    std::set<std::string> used_paths;
    std::string base_dir;  //!< folder of the case file ("" for parsed text)
  };
  CaseNode(const nlohmann::json* json, std::string path, std::shared_ptr<Usage> usage)
      : json_(json), path_(std::move(path)), usage_(std::move(usage)) {}

  const nlohmann::json& value(const std::string& key) const;

  const nlohmann::json* json_;
  std::string path_;
  std::shared_ptr<Usage> usage_;
};

//! A whole case file: owns the JSON, hands out the root node, finds unused keys.
class CaseDocument {
 public:
  //! Parse `text`; a syntax error becomes a CaseError at path "(file)".
  static CaseDocument parse(const std::string& text);
  //! Read and parse a file; a missing file is a CaseError too.
  static CaseDocument load(const std::string& filename);

  CaseNode root() const;
  //! Throw a CaseError naming the first key (in key order) that no reader used.
  //! Keys that start with '_' are comments and never reported.
  void check_all_used() const;

 private:
  explicit CaseDocument(nlohmann::json json);
  std::shared_ptr<const nlohmann::json> json_;
  std::shared_ptr<CaseNode::Usage> usage_;
};

}  // namespace mpm_lig
