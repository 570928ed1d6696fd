#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/case_node.h"

namespace mpm_lig {

//! Named variants chosen by a string in the case file: materials, shape functions, analyses
//! (DEM engines are modules loaded by dlopen: dem::create_engine). Each family registers its
//! members in one .cpp file; an unknown name is a CaseError that lists the known ones.
template <class Product, class... Args>
class Registry {
 public:
  using Creator = std::function<std::unique_ptr<Product>(Args...)>;

  //! Register `name`; a name registered twice is a programming error (std::logic_error), not
  //! a silent replacement of the first variant.
  void add(const std::string& name, Creator creator) {
    if (!creators_.emplace(name, std::move(creator)).second)
      throw std::logic_error("registry: '" + name + "' is registered twice");
  }

  bool contains(const std::string& name) const { return creators_.count(name) != 0; }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : creators_)
      out.push_back(entry.first);
    return out;
  }

  //! Create the variant named by `node.key`, forwarding `args`.
  std::unique_ptr<Product> create(const CaseNode& node, const std::string& key,
                                  Args... args) const {
    return create(node.choice(key, names()), std::forward<Args>(args)...);
  }

  std::unique_ptr<Product> create(const std::string& name, Args... args) const {
    return creators_.at(name)(std::forward<Args>(args)...);
  }

 private:
  std::map<std::string, Creator> creators_;
};

}  // namespace mpm_lig
