#pragma once

#include <cstddef>
#include <string>

namespace mpm_lig {

//! Largest case file mpm_lig reads: the largest shipped case is a few kB; a bigger file is a
//! wrong file (a results file, a device) rather than a case.
inline constexpr std::size_t kMaxCaseFileBytes = 16u << 20;
//! Deepest nesting of objects and arrays in a case (the shipped cases use 5 levels).
inline constexpr int kMaxCaseDepth = 64;

//! JSON path of `key` in the object at `parent` ("a.b"), and of element `i` of an array ("a[3]").
std::string json_path_key(const std::string& parent, const std::string& key);
std::string json_path_index(const std::string& parent, std::size_t i);

//! The text of a case file: a CaseError at "(file)" unless `filename` names a regular file
//! (not a folder, device or pipe) of at most kMaxCaseFileBytes bytes that can be read.
std::string read_case_text(const std::string& filename);

//! Checks a case's text before it is parsed into a document, so that no input can crash or
//! mislead the parser: NUL bytes, nesting deeper than kMaxCaseDepth, a key given twice in one
//! object (JSON would silently keep one), numbers beyond the range of a double, and any
//! syntax error. Every problem is a CaseError naming the JSON path where it was found (syntax
//! errors: "(file)", with the line, column and the path near them).
void check_case_text(const std::string& text);

}  // namespace mpm_lig
