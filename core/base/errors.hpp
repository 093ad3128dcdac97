#pragma once
#include <stdexcept>
#include <string>

namespace closurelab {

// Bad configuration: names the JSON path that is wrong (e.g. "/cells/3/kernel/eta").
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string json_path, const std::string& message)
      : std::runtime_error(json_path.empty() ? message : json_path + ": " + message),
        path_(std::move(json_path)),
        message_(message) {}
  const std::string& path() const { return path_; }
  const std::string& message() const { return message_; }

 private:
  std::string path_, message_;
};

// A computation that produced a non-finite or otherwise invalid value.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace closurelab
