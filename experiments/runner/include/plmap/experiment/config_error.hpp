#pragma once
/// \file
/// ConfigError: an experiment configuration that cannot be run. The message always names the
/// key it is about (`pipeline[1].locator`, `sweep."evaluate.threads"[2]`, `plots[0].y`), so a
/// user can find the line to fix.

#include <plmap/core/errors.hpp>

#include <string>

namespace plmap::experiment {

class ConfigError : public Error {
 public:
  /// `source` is the config file (may be empty), `key` the dotted key path, `what` the problem.
  ConfigError(const std::string& source, std::string key, const std::string& what)
      : Error((source.empty() ? "" : source + ": ") + (key.empty() ? "" : key + ": ") + what),
        key_(std::move(key)) {}
  /// The key the error is about, as written in the message.
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

}  // namespace plmap::experiment
