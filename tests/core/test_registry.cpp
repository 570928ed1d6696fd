#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "core/registry.h"

using namespace mpm_lig;

namespace {

struct Variant {
  int id;
};
using VariantRegistry = Registry<Variant>;

VariantRegistry::Creator make(int id) {
  return [id] { return std::make_unique<Variant>(Variant{id}); };
}

}  // namespace

TEST(Registry, CreatesTheVariantRegisteredUnderAName) {
  VariantRegistry registry;
  registry.add("a", make(1));
  registry.add("b", make(2));
  EXPECT_EQ(registry.create("b")->id, 2);
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"a", "b"}));
}

TEST(Registry, RefusesANameRegisteredTwiceAndKeepsTheFirst) {
  VariantRegistry registry;
  registry.add("a", make(1));
  EXPECT_THROW(registry.add("a", make(2)), std::logic_error);
  EXPECT_EQ(registry.create("a")->id, 1);
}
