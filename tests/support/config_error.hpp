#pragma once
// Test helper: the message of the ConfigError that `f` throws, or "" when it throws none.
#include <functional>
#include <string>

#include "core/base/errors.hpp"

namespace closurelab::test_support {

inline std::string config_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace closurelab::test_support
