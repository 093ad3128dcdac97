#include <gtest/gtest.h>

#include "core/registry.hpp"

TEST(Registry, HasBuiltins) { EXPECT_TRUE(closurelab::builtin_registry().kernels.contains("gaussian")); }
